#!/bin/bash
#SBATCH --job-name=impacts
#SBATCH --ntasks=64
#SBATCH --cpus-per-task=1
#SBATCH --time=02:00:00
#SBATCH --output=impacts-%j.out

# One rank per partition; the Python driver runs on the first node and only
# builds scenes and reads results, so it needs no cores of its own.
module load lammps openmpi python      # or whatever provides lmp, mpirun, python3
cd "$SLURM_SUBMIT_DIR"
source .venv/bin/activate               # numpy, scipy, MDAnalysis, matplotlib (make setup)
export PATH="$PWD/.venv/bin:$PATH"      # lmp's embedded Python must find the same packages

IMPACT_MPIRUN="srun --ntasks=$SLURM_NTASKS" \
    python -m runner study paper --partitions "$SLURM_NTASKS"
