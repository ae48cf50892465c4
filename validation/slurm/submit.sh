#!/usr/bin/env bash
# Submits a phdslam experiment to Slurm: a job array with one shard per task, and a job that
# waits for every task (afterok), merges the shards and writes the HTML report.
#
#   validation/slurm/submit.sh EXPERIMENT OUT SHARDS [phdslam run options...]
#
#   EXPERIMENT  experiment file (validation/experiments/*.yaml)
#   OUT         folder on a file system every node sees; it receives
#                 OUT/shards/shard-<i>/     the results folder of array task i (phdslam run --shard i/SHARDS)
#                 OUT/merged/               the merged results folder (phdslam merge)
#                 OUT/merged/report/        index.html of the report (reports/make_report.py)
#                 OUT/slurm/shard.sh, merge.sh  the job scripts (resubmit them to resume)
#                 OUT/slurm/logs/           the jobs' stdout and stderr
#   SHARDS      number of array tasks (1 to 1000, Slurm's default MaxArraySize)
#   options     passed to every `phdslam run` (e.g. --steps 200 --seeds 1-20); not --out,
#               --shard, --experiment nor --jobs, which the script sets itself
#
# Environment:
#   PHDSLAM          the program (default: phdslam on PATH, else build/release/apps/phdslam)
#   PHDSLAM_PYTHON   Python for the report (default: python3)
#   PHDSLAM_CPUS     CPUs per array task, also its --jobs (1 to 1024; default: 1)
#   SBATCH_EXTRA     further sbatch options for both jobs, split on spaces (e.g.
#                    "--partition=long --time=02:00:00")
#
# Every argument is checked, and sbatch looked for, before anything is written.
# Prints "array <job id>" and "merge <job id>". Exit codes: 0 submitted, 2 usage error (also:
# no sbatch on PATH), else the status of the failing sbatch.
set -euo pipefail

usage() {
  sed -n '2,30p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
[[ $# -ge 3 ]] || usage
experiment=$1
out=$2
shards=$3
shift 3
[[ -f "$experiment" ]] || { echo "submit.sh: no experiment file '$experiment'" >&2; exit 2; }
[[ -n "$out" ]] || { echo "submit.sh: OUT is empty" >&2; exit 2; }
fail() { echo "submit.sh: $*" >&2; exit 2; }
[[ "$shards" =~ ^[1-9][0-9]{0,3}$ && "$shards" -le 1000 ]] ||
  fail "SHARDS must be a whole number from 1 to 1000, got '$shards'"
cpus=${PHDSLAM_CPUS:-1}
[[ "$cpus" =~ ^[1-9][0-9]{0,3}$ && "$cpus" -le 1024 ]] ||
  fail "PHDSLAM_CPUS must be a whole number from 1 to 1024, got '$cpus'"
for option in "$@"; do
  case "$option" in
    --out|--out=*|--shard|--shard=*|--experiment|--experiment=*|--jobs|--jobs=*)
      fail "option '${option%%=*}' is set by the script for every task; remove it" ;;
  esac
done
command -v sbatch >/dev/null ||
  fail "sbatch not found on PATH (run this on a Slurm login node); nothing was written"

root=$(cd "$(dirname "$0")/../.." && pwd)
program=${PHDSLAM:-}
if [[ -z "$program" ]]; then
  program=$(command -v phdslam || true)
  [[ -n "$program" ]] || program="$root/build/release/apps/phdslam"
fi
[[ -f "$program" && -x "$program" ]] || fail "phdslam program '$program' not found (set PHDSLAM)"
program=$(realpath "$program")
python=${PHDSLAM_PYTHON:-python3}
experiment=$(realpath "$experiment")
mkdir -p "$out"
out=$(realpath "$out")
mkdir -p "$out/shards" "$out/slurm/logs"
read -r -a extra_sbatch <<< "${SBATCH_EXTRA:-}"
name=$(basename "$experiment" .yaml)

# A job script whose command is the quoted words given.
write_script() {
  local file=$1
  shift
  {
    echo "#!/usr/bin/env bash"
    echo "set -euo pipefail"
    printf '%s\n' "$@"
  } > "$file"
  chmod +x "$file"
}

run_words=$(printf '%q ' "$program" run --experiment "$experiment" --quiet "$@")
write_script "$out/slurm/shard.sh" \
  "# Array task i: shard i of $shards. Rerun one task: sbatch --array=i $out/slurm/shard.sh" \
  "task=\${SLURM_ARRAY_TASK_ID:?run as a Slurm array task}" \
  "exec $run_words--jobs \"\${SLURM_CPUS_PER_TASK:-$cpus}\" --shard \"\$task/$shards\" --out $(printf '%q' "$out/shards")/shard-\"\$task\""

merge_words=$(printf '%q ' "$program" merge --out "$out/merged")
report_words=$(printf '%q ' "$python" "$root/reports/make_report.py" "$out/merged" --out "$out/merged/report")
write_script "$out/slurm/merge.sh" \
  "# Merges every shard folder present and writes the report; safe to rerun." \
  "shopt -s nullglob" \
  "shard_dirs=($(printf '%q' "$out/shards")/shard-*)" \
  "[[ \${#shard_dirs[@]} -gt 0 ]] || { echo 'merge.sh: no shard folder' >&2; exit 1; }" \
  "$merge_words\"\${shard_dirs[@]}\"" \
  "$report_words"

array_id=$(sbatch --parsable --job-name="$name" --array="1-$shards" --cpus-per-task="$cpus" \
  --output="$out/slurm/logs/shard-%a.out" --error="$out/slurm/logs/shard-%a.err" \
  --chdir="$out" "${extra_sbatch[@]}" "$out/slurm/shard.sh")
array_id=${array_id%%;*}
merge_id=$(sbatch --parsable --job-name="$name-merge" --dependency="afterok:$array_id" \
  --kill-on-invalid-dep=yes --output="$out/slurm/logs/merge.out" \
  --error="$out/slurm/logs/merge.err" --chdir="$out" "${extra_sbatch[@]}" "$out/slurm/merge.sh")
merge_id=${merge_id%%;*}
echo "array $array_id"
echo "merge $merge_id"
