"""Warp twins of ``cclouds/media.h`` (entries are added as they are implemented)."""
from __future__ import annotations
