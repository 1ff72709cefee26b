"""Catalog of supported instructions: name → FunctionBlock class (feeds the kernel and GET /api/v1/fb-types)."""

from __future__ import annotations

from .admin import ADMIN_CLASSES
from .base import FunctionBlock
from .cam_fb import CAM_CLASSES
from .common import COMMON_CLASSES
from .group_motion_fb import GROUP_CLASSES
from .homing_fb import HOMING_CLASSES
from .latch import LATCH_CLASSES
from .robot_fb import ROBOT_CLASSES
from .robot_jog import ROBOT_JOG_CLASSES
from .robot_motion_fb import ROBOT_MOTION_CLASSES
from .single_axis import FB_CLASSES
from .sync_fb import SYNC_CLASSES
from .timestamp import TIMESTAMP_CLASSES
from .torque import TORQUE_CLASSES

ALL_CLASSES: tuple[type[FunctionBlock], ...] = (*FB_CLASSES, *ADMIN_CLASSES, *HOMING_CLASSES, *COMMON_CLASSES,
                                                *LATCH_CLASSES, *TORQUE_CLASSES, *SYNC_CLASSES,
                                                *CAM_CLASSES, *TIMESTAMP_CLASSES)
ALL_CLASSES = (*ALL_CLASSES, *GROUP_CLASSES)  # axes-group instructions (group_fb.py, group_motion_fb.py)
ALL_CLASSES = (*ALL_CLASSES, *ROBOT_CLASSES)  # robot instructions (robot_fb.py)
ALL_CLASSES = (*ALL_CLASSES, *ROBOT_MOTION_CLASSES)  # robot motion instructions (robot_motion_fb.py)
ALL_CLASSES = (*ALL_CLASSES, *ROBOT_JOG_CLASSES)  # MC Studio extension: Cartesian jog (robot_jog.py)
FB_TYPES: dict[str, type[FunctionBlock]] = {cls.DEF.name: cls for cls in ALL_CLASSES}
