function varargout = rand(varargin)
  % Shadows the built-in rand: the draw is made by the built-in and, while a run records, logged
  % with its purpose (phdslam_authors_log_draws). Calls that set or query the generator's state
  % pass straight through.
  if nargin > 0 && ischar(varargin{1})
    [varargout{1:nargout}] = builtin('rand', varargin{:});
    return
  end
  r = builtin('rand', varargin{:});
  phdslam_authors_log_draws(r, 'uniform');
  varargout{1} = r;
end
