function varargout = randn(varargin)
  % Shadows the built-in randn: the draw is made by the built-in and, while a run records, logged
  % with its purpose (phdslam_authors_log_draws). Calls that set or query the generator's state
  % pass straight through.
  if nargin > 0 && ischar(varargin{1})
    [varargout{1:nargout}] = builtin('randn', varargin{:});
    return
  end
  r = builtin('randn', varargin{:});
  phdslam_authors_log_draws(r, 'normal');
  varargout{1} = r;
end
