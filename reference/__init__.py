"""The project's own implementation of the impact model, independent of LAMMPS.

Written without sharing any force code with the LAMMPS style, so that the two
can check each other.
"""
