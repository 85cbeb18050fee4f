#!/bin/bash
# A study on Slurm: this small job is the driver; it submits the workers as
# batch jobs of their own (dask-jobqueue), replaces any that end early, and
# cancels them when it ends. Submit it from the project's folder (make setup
# done there):
#
#   sbatch docs/cluster/slurm_study.sh                       # the paper study
#   sbatch docs/cluster/slurm_study.sh demo --samples 8      # any study; options override
#
# Killed by its time limit or scancel, it cancels the workers' jobs and exits;
# submit it again and it runs what is missing.
#SBATCH --job-name=impacts-driver
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --time=12:00:00
#SBATCH --output=impacts-driver-%j.out
set -euo pipefail
cd "$SLURM_SUBMIT_DIR"
study=${1:-paper}
shift || true
# 4 jobs of 16 workers, each job at most 2 hours: set these to your site's
# nodes and limits (and --queue, --account, --memory).
exec .venv/bin/python -m runner study "$study" --cluster slurm --jobs 4 --cores-per-job 16 \
    --walltime 02:00:00 "$@"
