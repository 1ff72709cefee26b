"""MC Studio: an open engineering studio for PLCopen motion control with an emulated NJ/NX-style controller."""

__version__ = "0.1.0"
