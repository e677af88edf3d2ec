"""Warp twins of ``cclouds/reproj.h`` (entries are added as they are implemented)."""
from __future__ import annotations
