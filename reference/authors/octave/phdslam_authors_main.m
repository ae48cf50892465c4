function phdslam_authors_main(release, mex_dir, export_dir, seeds, out_dir, variant, particles, trace_root, map_every, draws_only)
  % Entry point of reference/authors/run_authors.py: puts the release's shared M files, the MEX
  % files built from its sources (mex_dir) and this folder's recording wrappers on the path (the
  % wrappers first), then runs phdslam_authors_run on every seed. trace_root: '' for no trace,
  % else the traces go to trace_root/seed-<s>/; draws_only: only draws.csv and estimate.csv.
  if nargin < 10
    draws_only = false;
  end
  here = fileparts(mfilename('fullpath'));
  warning('off', 'Octave:shadowed-function');
  addpath(fullfile(release, 'Shared Files', 'shared m files'));
  addpath(mex_dir);
  addpath(here);
  addpath(fullfile(here, 'recording'));
  for s = seeds
    % The release seeds Matlab's Mersenne twister with the data's seed (simulation_setup.m).
    rand('twister', s);
    randn('twister', s);
    trace_dir = '';
    if ~isempty(trace_root)
      trace_dir = fullfile(trace_root, sprintf('seed-%d', s));
    end
    tic;
    phdslam_authors_run(export_dir, s, out_dir, variant, particles, trace_dir, map_every, draws_only);
    fprintf('seed %d: %d particles, %s, %.1f s\n', s, particles, variant, toc);
  end
end
