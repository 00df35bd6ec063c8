function code_trials(work, n, sigma, first, count, seed, out)
  % Runs trials first..first+count-1 of the authors' MCTSgaussian.m (copied
  % into WORK by run_code.sh) at lattice side N and Gaussian sigma, and
  % appends one CSV row per trial to OUT. Trial i seeds rand and randn with
  % SEED*1e6 + i, so any trial can be regenerated on its own. A trial the
  % script stops with an error is recorded with steps -1.
  addpath(work);
  pkg load statistics;            % normrnd, called by gausstarget.m
  fid = fopen(out, 'a');
  if fid < 0
    error('cannot open %s for appending', out);
  end
  for i = first:(first + count - 1)
    s = seed * 1e6 + i;
    rand('state', s);
    randn('state', s);
    t0 = tic;
    try
      [steps, opt, tx, ty] = one_trial(n, sigma);
    catch err
      % The script can stop with an index error (its left expansion writes
      % Nx(Sx, Sy+1) without mod1, index 0 when Sx = 0): recorded as -1.
      fprintf(stderr, 'trial %d: %s\n', i, err.message);
      [steps, opt, tx, ty] = deal(-1, -1, -1, -1);
    end
    fprintf(fid, '%d,%d,%g,%d,%d,%d,%d,%d,%.1f\n', i, n, sigma, s, steps, opt, tx, ty, toc(t0));
    fflush(fid);
  end
  fclose(fid);
end

function [steps, opt, tx, ty] = one_trial(N_, sigma_)
  % The script reads N and sigma from the two globals the driver set into
  % its parameter lines; it runs in this function's workspace.
  global FIDELITY_N FIDELITY_SIGMA
  FIDELITY_N = N_;
  FIDELITY_SIGMA = sigma_;
  MCTSgaussian_fidelity;
  steps = MCTS(1);
  opt = MOPT(1);
  tx = FIDELITY_TX;
  ty = FIDELITY_TY;
end
