function obj = sample(obj, wp, mp, Pp, r_uniform, r_gaussian)
  % Wraps the release's sample MEX (built as authors_sample): records the particle's predicted
  % pose Gaussian, its proposal mixture, and the sampled pose and log-weight.
  global PHDSLAM_REC
  prior_xn = obj.xn;
  prior_Pn = obj.Pn;
  wp_in = wp(:)';
  obj = authors_sample(obj, wp, mp, Pp, r_uniform, r_gaussian);
  if isempty(PHDSLAM_REC) || ~PHDSLAM_REC.active || PHDSLAM_REC.trace_fids.particles < 0
    return
  end
  i = PHDSLAM_REC.sample_count;
  PHDSLAM_REC.sample_count = i + 1;
  k = PHDSLAM_REC.step;
  P = prior_Pn;
  fprintf(PHDSLAM_REC.trace_fids.particles, ...
          '%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g,%.17g,%.17g\n', ...
          k, i, prior_xn(1), prior_xn(2), prior_xn(3), P(1,1), P(1,2), P(1,3), P(2,2), P(2,3), ...
          P(3,3), numel(wp_in), obj.xn(1), obj.xn(2), obj.xn(3), obj.w);
  for j = 1:numel(wp_in)
    m = mp(:, j);
    C = Pp(:, :, j);
    fprintf(PHDSLAM_REC.trace_fids.proposals, ...
            '%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n', ...
            k, i, j - 1, wp_in(j), m(1), m(2), m(3), C(1,1), C(1,2), C(1,3), C(2,2), C(2,3), C(3,3));
  end
end
