"""Warp twins of ``cclouds/clouds.h`` (entries are added as they are implemented)."""
from __future__ import annotations
