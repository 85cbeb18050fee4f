"""Impacts and studies run by LAMMPS (runner/): the deck, the sweep, its folders, Slurm."""
