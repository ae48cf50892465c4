function obj = hypothesisReductionAlgorithm(obj, params)
  % Wraps the release's hypothesis reduction MEX (built as authors_hypothesisReductionAlgorithm):
  % records the particle after its update and reduction (log-weight, map sizes, the map itself on
  % the steps whose maps are recorded).
  global PHDSLAM_REC
  obj = authors_hypothesisReductionAlgorithm(obj, params);
  if isempty(PHDSLAM_REC) || ~PHDSLAM_REC.active || PHDSLAM_REC.trace_fids.states < 0
    return
  end
  i = PHDSLAM_REC.reduce_count;
  PHDSLAM_REC.reduce_count = i + 1;
  k = PHDSLAM_REC.step;
  fprintf(PHDSLAM_REC.trace_fids.states, '%d,%d,%.17g,%d,%d,%d\n', k, i, obj.w, ...
          numel(obj.eta), numel(obj.eta_p), size(obj.birth_y, 2));
  if PHDSLAM_REC.map_every > 0 && (mod(k, PHDSLAM_REC.map_every) == 0 || k == PHDSLAM_REC.last_step)
    write_components(PHDSLAM_REC.trace_fids.maps, k, i, 0, obj.eta, obj.xl, obj.Pl);
    write_components(PHDSLAM_REC.trace_fids.maps, k, i, 1, obj.eta_p, obj.xl_p, obj.Pl_p);
  end
end

function write_components(fid, k, i, list, eta, xl, Pl)
  for c = 1:numel(eta)
    fprintf(fid, '%d,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n', k, i, list, c - 1, eta(c), ...
            xl(1, c), xl(2, c), Pl(1, 1, c), Pl(1, 2, c), Pl(2, 2, c));
  end
end
