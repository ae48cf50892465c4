function phdslam_authors_log_draws(r, kind)
  % Appends draws to draws.csv as step,particle,purpose,index,value. Purposes: "component"
  % (rbpf_phd's rand(1,N): one uniform per particle), "pose" (rbpf_phd's randn(3,N): three
  % normals per particle, index 0..2), "resample" (resample's rand(N,1): uniform j of the
  % stratified walk, particle = j).
  global PHDSLAM_REC
  if isempty(PHDSLAM_REC) || ~PHDSLAM_REC.active || PHDSLAM_REC.draws_fid < 0
    return
  end
  stack = dbstack();
  caller = '';
  if numel(stack) >= 3
    caller = stack(3).name;
  end
  fid = PHDSLAM_REC.draws_fid;
  step = PHDSLAM_REC.step;
  if strcmp(caller, 'rbpf_phd') && strcmp(kind, 'uniform')
    for i = 1:numel(r)
      fprintf(fid, '%d,%d,component,0,%.17g\n', step, i - 1, r(i));
    end
  elseif strcmp(caller, 'rbpf_phd') && strcmp(kind, 'normal')
    for i = 1:size(r, 2)
      for d = 1:size(r, 1)
        fprintf(fid, '%d,%d,pose,%d,%.17g\n', step, i - 1, d - 1, r(d, i));
      end
    end
  elseif strcmp(caller, 'resample') && strcmp(kind, 'uniform')
    for i = 1:numel(r)
      fprintf(fid, '%d,%d,resample,0,%.17g\n', step, i - 1, r(i));
    end
  else
    error('phdslam_authors_log_draws: a %s draw from ''%s'' has no known purpose', kind, caller);
  end
end
