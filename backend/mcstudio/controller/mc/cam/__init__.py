"""Cam tables of the MC function module: the data model (`_sMC_CAM_REF` arrays, end point, CSV files), the curve
laws of `_eMC_CAM_CURVE`, MC_GenerateCamTable and the characteristics the cam editor shows. Pure functions over
numpy arrays; the instructions (FBs) that use them live in `mc/fb`. See docs/cams.md."""

from .analysis import Jump, Kinematics, ProfileCharacteristics, continuity, kinematics, profile_characteristics
from .csvio import CamCsvError, format_cam_csv, parse_cam_csv, read_cam_csv, write_cam_csv
from .curves import LAWS, CurveCharacteristics, _eMC_CAM_CURVE, characteristics, evaluate
from .generate import (
    CamProfile,
    CamSegment,
    GenerateError,
    GenerateResult,
    _sMC_CAM_NODE,
    _sMC_CAM_PROPERTY,
    generate,
    generate_into,
    plan,
)
from .table import MAX_POINTS, REAL, CamTable, CamTableSet, EndPoint, find_end_point

__all__ = [
    "LAWS",
    "MAX_POINTS",
    "REAL",
    "CamCsvError",
    "CamProfile",
    "CamSegment",
    "CamTable",
    "CamTableSet",
    "CurveCharacteristics",
    "EndPoint",
    "GenerateError",
    "GenerateResult",
    "Jump",
    "Kinematics",
    "ProfileCharacteristics",
    "_eMC_CAM_CURVE",
    "_sMC_CAM_NODE",
    "_sMC_CAM_PROPERTY",
    "characteristics",
    "continuity",
    "evaluate",
    "find_end_point",
    "format_cam_csv",
    "generate",
    "generate_into",
    "kinematics",
    "parse_cam_csv",
    "plan",
    "profile_characteristics",
    "read_cam_csv",
    "write_cam_csv",
]
