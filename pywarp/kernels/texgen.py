"""Warp twins of ``cclouds/texgen.h`` (entries are added as they are implemented)."""
from __future__ import annotations
