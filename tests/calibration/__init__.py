"""The materials' calibration (calibration/)."""
