"""Builds the lattices of the impact model and writes LAMMPS data files.

Lengths are in units of the disk radius R, masses in units of one point's
mass m, and spring constants are chosen so that the disk's elastic wave speed
c is 1: velocities come out in units of c and times in units of R / c
(docs/model.md section 3).
"""
