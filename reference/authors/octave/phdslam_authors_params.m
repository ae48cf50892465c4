function params = phdslam_authors_params(models, variant, particles)
  % The parameter struct the authors' synthetic-data filter reads, filled from an export's
  % models.json (the scenario's noise, field of view, detection and clutter) and the filter
  % settings of the paper's synthetic experiments. variant: 'phd3' (Murty hypotheses J = 50,
  % IPL L = 5) or 'phd1' (J = 0: the predicted pose Gaussian as the proposal).
  sensor = models.sensor;
  params.f_mode = false;
  params.visualize_passive_components = false;
  params.dt = 1;
  params.fov_range = sensor.fov_range;
  params.fov_angle = sensor.fov_half_angle;
  params.range_buffer = sensor.range_buffer;
  params.angle_buffer = sensor.angle_buffer;
  params.lambda = sensor.clutter_rate;
  params.lambda_c = sensor.clutter_intensity;
  params.P_D = sensor.pd_max;
  params.P_B = 1e-6;
  params.P_G = 1e-9;
  % chi-square quantile with 2 degrees of freedom in closed form: -2 log(P_G).
  params.gating_size = -2 * log(params.P_G);
  params.w_min = log(1e-6);
  params.merging_threshold = 50;
  params.etaT = log((1 - sensor.pd_nominal)^2);
  params.resample = true;
  params.N_particle = particles;
  params.T_eff = 0.2;
  params.N_eff = params.T_eff * particles;
  params.J = 50;
  params.DA_threshold = log(10^(-3));
  params.L = 5;
  params.epsilon = 1e-3;
  if strcmp(variant, 'phd1')
    params.J = 0;
    params.L = 0;
  elseif ~strcmp(variant, 'phd3')
    error('phdslam_authors_params: unknown variant ''%s'' (phd3 or phd1)', variant);
  end
  params.xn_dim = 3;
  params.xl_dim = 2;
  params.u_dim = 2;
  params.h_dim = 2;
  params.Qn = diag([1e-9 1e-9 1e-18]);
  params.Qu = matrix_2x2(models.motion.control_noise_cov);
  params.R = matrix_2x2(sensor.noise_cov);
  % Read by the hypothesis reduction's MEX source but never used there; the release's own
  % parameter setup does not define it.
  params.M_cap = 1e6;
  params.MEX = true;
end

function m = matrix_2x2(value)
  % models.json writes a 2 x 2 matrix as a list of rows; jsondecode gives it as a matrix.
  if iscell(value)
    value = cell2mat(cellfun(@(r) r(:)', value, 'UniformOutput', false));
  end
  m = reshape(value, 2, 2);
  if isvector(value)
    m = reshape(value, 2, 2)';
  end
end
