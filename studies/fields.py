"""A check the studies' Params share: their float fields hold numbers. nan passes no comparison
(a range check written as ``not x >= 0`` would be needed everywhere) and inf passes the lower
bounds; a trial would then divide by it, or run until a time it never reaches."""

from __future__ import annotations

import dataclasses
import math
from typing import Optional


def non_finite(params) -> Optional[str]:
    """The name of the first float field of the dataclass ``params`` that is nan or infinite."""
    for field in dataclasses.fields(params):
        value = getattr(params, field.name)
        if isinstance(value, float) and not math.isfinite(value):
            return field.name
    return None
