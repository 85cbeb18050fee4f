"""Measures E, the Poisson ratio and the wave speed of each lattice (MODEL.md section 3)."""
