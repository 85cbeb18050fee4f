"""The bodies of the samples a worker runs, kept as binary restarts."""

from __future__ import annotations

import json
import os
import socket
from dataclasses import asdict
from pathlib import Path

from builder.lammps_data import write_bodies
from ground.checks import word_problem
from ground.errors import InputError
from ground.gate import make_folder
from ground.launch import data_to_restart

# Where a study's workers keep the bodies of the samples they run: a folder
# per worker process under the study's folder, which the driver removes when
# the study's run ends (a worker that LAMMPS ended cannot clean up itself).
BODIES_FOLDER = ".bodies"


class SampleBodies:
    """The bodies of the samples this process runs, as binary restarts of
    their data files: one per sample (its bodies in their own frames, which
    its angles and speeds share; the deck places the disk), in the study's
    runs/<study>/.bodies/<host>-<pid>/, the last few kept. Only the disk's
    placement and velocity differ between a sample's impacts
    (builder.lammps_data); the restart is read in a tenth of the data file's
    time, into the same atoms in the same order (tests/test_sample_bodies.py;
    on one rank: on several, LAMMPS splits the box among them, and a restart
    of the unplaced bodies has another box than a placed data file)."""

    KEPT = 8

    def __init__(self) -> None:
        self.files: dict[str, Path] = {}
        self.written = 0

    def path(self, scene, springs: str, study_folder: Path, log: Path) -> Path:
        """The restart of ``scene``'s sample, written if this process has not.

        LAMMPS writes it with its log in ``log`` (an impact's log.lammps: an
        error there, which ends this process, is its impact's failure).

        Raises
        ------
        ground.errors.InputError
            If the folder's path is not one word, which LAMMPS needs.
        """
        spec = asdict(scene.spec)
        for placement in ("gamma_deg", "vn", "contact_time_guess", "start_gap"):
            spec.pop(placement)
        key = json.dumps([spec, springs, str(study_folder)], sort_keys=True)
        # a run of the study that ended removed its workers' folders, also
        # under a worker that a joined cluster keeps for the next run
        if key not in self.files or not self.files[key].is_file():
            folder = study_folder / BODIES_FOLDER / f"{socket.gethostname()}-{os.getpid()}"
            if problem := word_problem(str(folder)):
                raise InputError(f"the workers' folder for the bodies {problem}: {folder}")
            make_folder(folder)
            self.files.pop(key, None)
            if len(self.files) >= self.KEPT:
                self.files.pop(next(iter(self.files))).unlink(missing_ok=True)
            self.written += 1
            data = folder / f"{scene.spec.lattice}-s{scene.spec.seed}-{self.written}.data"
            write_bodies(scene, data, springs)
            self.files[key] = data_to_restart(data, data.with_suffix(".restart"), springs, log)
            data.unlink()
        return self.files[key]


SAMPLE_BODIES = SampleBodies()
