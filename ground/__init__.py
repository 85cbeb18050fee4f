"""The ground every room of the project stands on: where things are
(``paths``), what bad input looks like (``errors``, ``checks``), what a
result records of its making (``provenance``), and how LAMMPS is started
(``launch``).

Nothing here imports another package of the project (tests/test_layers.py),
so builder, analysis, runner, reference, calibration and bench may all use it.
"""
