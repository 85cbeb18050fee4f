"""A study's numbers with their errors: the seed bootstrap (seeds.py), the fits
and model-free measures (fits.py, measures.py, estimates.py), the verdicts on
the paper's claims (claims.py, resolution_claims.py, fit_verdicts.py), and
the limits as the resolution grows (extrapolation.py, levels.py,
ensemble.py)."""
