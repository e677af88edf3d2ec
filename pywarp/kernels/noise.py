"""Warp twins of ``cclouds/noise.h`` (entries are added as they are implemented)."""
from __future__ import annotations
