"""Runs impacts: builds a scene, runs the LAMMPS deck on it, analyses the outputs."""
