"""The theories the numbers are compared with: Walton's and the compliant
(Maw-Barber-Fawcett) beta(psi) (tangential.py), and the smooth disk's normal
impact (continuum_smooth.py, modal_smooth.py)."""
