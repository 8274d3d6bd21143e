#!/bin/bash
# A job of `simlab slurm`, for sbatch: its header, its resources, and the one command it runs.
# (simlab slurm writes it from grader/cli/scripts/slurm-job.sh, its values in for the @...@ words.)
@HEADER@
#SBATCH --job-name=@NAME@
@ARRAY@
#SBATCH --cpus-per-task=@CPUS@
#SBATCH --output=@OUTPUT@
#SBATCH --chdir=@CHDIR@
@EXTRA@
set -euo pipefail
exec @COMMAND@
