"""One impact measured: its series and dumps read (series.py, dump.py), e and
beta from the motion (restitution.py, binary.py for two disks), result.json
(result.py), the wall's tilt (tilt.py) and impacts without a result
(failures.py)."""
