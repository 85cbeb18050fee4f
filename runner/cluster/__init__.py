"""Where a study's workers come from (workers.py), what the driver submits to
them and records (driver.py), and what each worker does (tasks.py)."""
