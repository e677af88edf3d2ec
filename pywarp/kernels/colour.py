"""Warp twins of ``cclouds/colour.h`` (entries are added as they are implemented)."""
from __future__ import annotations
