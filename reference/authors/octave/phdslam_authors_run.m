function phdslam_authors_run(export_dir, seed, out_dir, variant, particles, trace_dir, map_every, draws_only)
  % Runs the authors' PHD-SLAM filter (their initialize, rbpf_phd, resample and MEX functions, on
  % the Octave path set up by phdslam_authors_main) on one seed of a `phdslam export` folder and
  % writes what `phdslam ingest` reads into out_dir/seed-<seed>/: trajectory.tum (the estimate at
  % every step), map.csv (the final map estimate with covariances) and timing.csv.
  % With a trace_dir, every random draw and the per-step particle states are written there too
  % (reference/authors/README.md describes the files); map_every > 0 records the full maps of
  % every particle each map_every steps and at the last step. draws_only: only draws.csv and
  % estimate.csv (what the replay needs), without the per-step particle states.
  global PHDSLAM_REC
  seed_dir = fullfile(export_dir, sprintf('seed-%d', seed));
  models = jsondecode(fileread(fullfile(seed_dir, 'models.json')));
  steps = read_table(fullfile(seed_dir, 'steps.csv'), 4);
  controls = read_table(fullfile(seed_dir, 'controls.csv'), 5);
  measurements = read_table(fullfile(seed_dir, 'measurements.csv'), 4);
  K = size(steps, 1);
  params = phdslam_authors_params(models, variant, particles);
  params.T = K;

  sim.x0 = models.initial_pose(:);
  sim.P0 = zeros(3);
  [obj, ~] = initialize(sim, params);

  recording = ~isempty(trace_dir);
  PHDSLAM_REC = struct('active', recording, 'step', 0, 'draws_fid', -1, 'sample_count', 0, ...
                       'reduce_count', 0, 'map_every', map_every, 'last_step', K - 1, ...
                       'trace_fids', struct('particles', -1, 'proposals', -1, 'states', -1, 'maps', -1));
  if recording
    if ~exist(trace_dir, 'dir'), mkdir(trace_dir); end
    PHDSLAM_REC.draws_fid = open_csv(trace_dir, 'draws.csv', 'step,particle,purpose,index,value');
  end
  if recording && ~draws_only
    PHDSLAM_REC.trace_fids.particles = open_csv(trace_dir, 'particles.csv', ...
        'step,particle,prior_x,prior_y,prior_theta,prior_pxx,prior_pxy,prior_pxt,prior_pyy,prior_pyt,prior_ptt,components,x,y,theta,log_weight_sampled');
    PHDSLAM_REC.trace_fids.proposals = open_csv(trace_dir, 'proposals.csv', ...
        'step,particle,component,log_weight,x,y,theta,pxx,pxy,pxt,pyy,pyt,ptt');
    PHDSLAM_REC.trace_fids.states = open_csv(trace_dir, 'states.csv', ...
        'step,particle,log_weight,active,passive,births');
    PHDSLAM_REC.trace_fids.maps = open_csv(trace_dir, 'maps.csv', ...
        'step,particle,list,component,log_weight,x,y,pxx,pxy,pyy');
  end
  if recording
    estimate_fid = open_csv(trace_dir, 'estimate.csv', 'step,x,y,theta,map_size,ess,resampled,sources');
  end

  poses = zeros(3, K);
  ms = zeros(1, K);
  est = [];
  c_row = 1;
  m_row = 1;
  for k = 0:K-1
    % Controls of step k: held over [t_start, t_end], in order; the authors' predict takes the time
    % stamps [t_start(1..c), t_end(c)] and one control column per interval.
    n_c = steps(k + 1, 3);
    if n_c > 0
      rows = controls(c_row:c_row + n_c - 1, :);
      c_row = c_row + n_c;
      t = [rows(:, 2)' rows(end, 3)];
      u = [rows(:, 4:5)' zeros(2, 1)];
    else
      t = steps(k + 1, 2);
      u = zeros(2, 1);
    end
    n_m = steps(k + 1, 4);
    if n_m > 0
      y = measurements(m_row:m_row + n_m - 1, 3:4)';
      m_row = m_row + n_m;
    else
      y = zeros(2, 0);
    end
    PHDSLAM_REC.step = k;
    PHDSLAM_REC.sample_count = 0;
    PHDSLAM_REC.reduce_count = 0;
    [obj, est] = rbpf_phd(obj, y, u, t, params);
    poses(:, k + 1) = est.m_hat;
    ms(k + 1) = est.dt * 1000;
    if recording
      sources = '';
      if est.resample
        sources = sprintf('%d ', [obj.iparent] - 1);
        sources = strtrim(sources);
      end
      fprintf(estimate_fid, '%d,%.17g,%.17g,%.17g,%d,%.17g,%d,%s\n', k, est.m_hat(1), ...
              est.m_hat(2), est.m_hat(3), size(est.mu_hat, 2), est.Neff * particles, ...
              est.resample, sources);
    end
  end
  PHDSLAM_REC.active = false;
  if recording
    fclose(PHDSLAM_REC.draws_fid);
    fclose(estimate_fid);
  end
  for fid = struct2cell(PHDSLAM_REC.trace_fids)'
    if fid{1} >= 0
      fclose(fid{1});
    end
  end
  write_outputs(fullfile(out_dir, sprintf('seed-%d', seed)), steps(:, 2), poses, est, ms);
end

function data = read_table(path, columns)
  % A CSV file with one header line; an empty table when it has no rows.
  text = fileread(path);
  lines = strsplit(strtrim(text), "\n");
  if numel(lines) <= 1
    data = zeros(0, columns);
    return
  end
  data = dlmread(path, ',', 1, 0);
  data = data(:, 1:columns);
end

function fid = open_csv(folder, name, header)
  fid = fopen(fullfile(folder, name), 'w');
  if fid < 0
    error('phdslam_authors_run: cannot write %s', fullfile(folder, name));
  end
  fprintf(fid, '%s\n', header);
end

function write_outputs(folder, times, poses, est, ms)
  if ~exist(folder, 'dir'), mkdir(folder); end
  fid = fopen(fullfile(folder, 'trajectory.tum'), 'w');
  for k = 1:numel(times)
    th = poses(3, k);
    fprintf(fid, '%.17g %.17g %.17g 0 0 0 %.17g %.17g\n', times(k), poses(1, k), poses(2, k), ...
            sin(th / 2), cos(th / 2));
  end
  fclose(fid);
  fid = fopen(fullfile(folder, 'map.csv'), 'w');
  fprintf(fid, 'x,y,pxx,pxy,pyy\n');
  for c = 1:size(est.mu_hat, 2)
    C = est.C_hat(:, :, c);
    fprintf(fid, '%.17g,%.17g,%.17g,%.17g,%.17g\n', est.mu_hat(1, c), est.mu_hat(2, c), C(1, 1), ...
            C(1, 2), C(2, 2));
  end
  fclose(fid);
  fid = fopen(fullfile(folder, 'timing.csv'), 'w');
  fprintf(fid, 'step,ms\n');
  fprintf(fid, '%d,%.17g\n', [0:numel(ms)-1; ms]);
  fclose(fid);
end
