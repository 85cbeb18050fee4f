"""The in-house reference integrator and LAMMPS against it (reference/)."""
