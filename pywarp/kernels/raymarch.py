"""Warp twins of ``cclouds/raymarch.h`` (entries are added as they are implemented)."""
from __future__ import annotations
