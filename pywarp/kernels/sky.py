"""Warp twins of ``cclouds/sky.h`` (entries are added as they are implemented)."""
from __future__ import annotations
