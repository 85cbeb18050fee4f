"""Reads the outputs of impact runs and measures e, beta and the contact."""
