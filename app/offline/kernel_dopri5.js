/* The integrator of the offline explorer's kernel (kernel.js): a port of the explicit
 * path of model/_kernel (dopri5.py, driver.py, event.py). The Dormand-Prince 5(4) pair
 * with its PI step-size control and its error norm over the motion and tau, Hairer and
 * Wanner's starting step, the exit (Eq. 9: first crossing of s(tau) = L0, located on the
 * 4th-order dense output and the step retaken to it) and the refinement of r_min, r_max at
 * turning points inside a step. No allocation inside a step.
 *
 * Works as a browser script (``MicropillarKernelDopri5``), in a Web Worker and in Node.
 */
(function (root, factory) {
  "use strict";
  var node = typeof module === "object" && module.exports;
  var api = factory(node ? require("./kernel_rhs.js") : root.MicropillarKernelRhs);
  if (node) module.exports = api;
  else root.MicropillarKernelDopri5 = api;
}(typeof self !== "undefined" ? self : this, function (S) {
  "use strict";
  var X = S.X, Y = S.Y, VX = S.VX, VY = S.VY, THETA = S.THETA, TAU = S.TAU, N = S.N,
      N_MOTION = S.N_MOTION;
  var restPosition = S.restPosition, makeRhs = S.makeRhs;
  var ERROR_SLOTS = [X, Y, VX, VY, THETA, TAU];
  var N_ERROR = 6;
  // Status codes (model.contact.results.Status).
  var OK = 0, STEP_BUDGET = 1, TIME_BUDGET = 2, STEP_UNDERFLOW = 3, NONFINITE = 4;
  // Step-size control (driver.py).
  var SAFETY = 0.9, PI_BETA = 0.04, LOG_EN_FLOOR = Math.log(1e-4), MAXFAC = 10.0;
  var ORDER = 5, EXPO = 1.0 / ORDER;
  var SCAN_POINTS = 8;
  var EPS = 2.220446049250313e-16;
  // Dormand-Prince 5(4) (dopri5.py: scipy's RK45 coefficients, Shampine's dense output).
  var A21 = 1 / 5;
  var A31 = 3 / 40, A32 = 9 / 40;
  var A41 = 44 / 45, A42 = -56 / 15, A43 = 32 / 9;
  var A51 = 19372 / 6561, A52 = -25360 / 2187, A53 = 64448 / 6561, A54 = -212 / 729;
  var A61 = 9017 / 3168, A62 = -355 / 33, A63 = 46732 / 5247, A64 = 49 / 176,
      A65 = -5103 / 18656;
  var B1 = 35 / 384, B3 = 500 / 1113, B4 = 125 / 192, B5 = -2187 / 6784, B6 = 11 / 84;
  var E1 = -71 / 57600, E3 = 71 / 16695, E4 = -71 / 1920, E5 = 17253 / 339200,
      E6 = -22 / 525, E7 = 1 / 40;
  var P_DENSE = [
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]
  ];


  function errNorm(err, y, ynew, rtol, atol) {
    for (var i = 0; i < N; i++) if (!isFinite(ynew[i])) return Infinity;
    var acc = 0.0;
    for (var k = 0; k < N_ERROR; k++) {
      var j = ERROR_SLOTS[k];
      var sc = atol + rtol * Math.max(Math.abs(y[j]), Math.abs(ynew[j]));
      var e = err[j] / sc;
      acc += e * e;
    }
    var v = Math.sqrt(acc / N_ERROR);
    return isFinite(v) ? v : Infinity;
  }

  /** Hairer & Wanner's starting step (driver.py ``_initial_step``). */
  function initialStep(y, f, rhs, rtol, atol, work, fwork) {
    var d0 = 0.0, d1 = 0.0, k, i, sc;
    for (k = 0; k < N_ERROR; k++) {
      i = ERROR_SLOTS[k];
      sc = atol + rtol * Math.abs(y[i]);
      d0 += Math.pow(y[i] / sc, 2);
      d1 += Math.pow(f[i] / sc, 2);
    }
    d0 = Math.sqrt(d0 / N_ERROR);
    d1 = Math.sqrt(d1 / N_ERROR);
    var h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    for (i = 0; i < N; i++) work[i] = y[i] + h0 * f[i];
    rhs(work, fwork);
    var d2 = 0.0;
    for (k = 0; k < N_ERROR; k++) {
      i = ERROR_SLOTS[k];
      sc = atol + rtol * Math.abs(y[i]);
      d2 += Math.pow((fwork[i] - f[i]) / sc, 2);
    }
    d2 = Math.sqrt(d2 / N_ERROR) / h0;
    var dm = Math.max(d1, d2);
    var h1 = dm <= 1e-15 ? Math.max(1e-6, h0 * 1e-3) : Math.exp(Math.log(0.01 / dm) / (ORDER + 1));
    return Math.min(100 * h0, h1);
  }

  /** Component i of the 4th-order continuous extension at t0 + th h (dopri5.py). */
  function dense(y, K, h, th, i) {
    var acc = 0.0;
    for (var j = 0; j < 7; j++) {
      var pj = P_DENSE[j];
      acc += K[j][i] * th * (pj[0] + th * (pj[1] + th * (pj[2] + th * pj[3])));
    }
    return y[i] + h * acc;
  }

  // ---------------------------------------------------------------- inside a step
  function hermite(y0, f0, y1, f1, h, th, i) {
    var h00 = (1 + 2 * th) * (1 - th) * (1 - th);
    var h10 = th * (1 - th) * (1 - th);
    var h01 = th * th * (3 - 2 * th);
    var h11 = th * th * (th - 1);
    return h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
  }

  function hermiteSlope(y0, f0, y1, f1, h, th, i) {
    return ((6 * th * th - 6 * th) * (y0[i] - y1[i]) + (3 * th * th - 4 * th + 1) * h * f0[i] +
            (3 * th * th - 2 * th) * h * f1[i]);
  }

  /** r at an extremum of r inside the step, or -1 (event.py ``r_inside``). */
  function rInside(y0, f0, y1, f1, h) {
    var glo = y0[X] * f0[X] + y0[Y] * f0[Y];
    var ghi = y1[X] * f1[X] + y1[Y] * f1[Y];
    if (!(glo * ghi < 0.0)) return -1.0;
    var lo = 0.0, hi = 1.0, r = -1.0, side = 0;
    for (var it = 0; it < 60; it++) {
      var th = (lo * ghi - hi * glo) / (ghi - glo);
      if (!(lo < th && th < hi)) th = 0.5 * (lo + hi);
      var x = hermite(y0, f0, y1, f1, h, th, X);
      var yy = hermite(y0, f0, y1, f1, h, th, Y);
      var g = x * hermiteSlope(y0, f0, y1, f1, h, th, X) + yy * hermiteSlope(y0, f0, y1, f1, h, th, Y);
      r = Math.sqrt(x * x + yy * yy);
      if (g === 0.0 || hi - lo <= 1e-12) break;
      if ((g < 0.0) === (glo < 0.0)) {
        lo = th; glo = g;
        if (side === -1) ghi *= 0.5;
        side = -1;
      } else {
        hi = th; ghi = g;
        if (side === 1) glo *= 0.5;
        side = 1;
      }
    }
    return r;
  }

  /** First theta in (0, 1] where s(tau) - L0 crosses zero on the dense output, or -1
   * (event.py ``locate_exit`` with the Dormand-Prince 5(4) extension). */
  function locateExit(h, y, ynew, K, x0, L0) {
    var gap = function (th) { return dense(y, K, h, th, TAU) - (dense(y, K, h, th, X) - x0) - L0; };
    var g1 = ynew[TAU] - (ynew[X] - x0) - L0;
    var lo = 0.0, glo = y[TAU] - (y[X] - x0) - L0, hi = -1.0, ghi = 0.0, g, th;
    for (var k = 1; k <= SCAN_POINTS; k++) {
      th = k / SCAN_POINTS;
      g = k === SCAN_POINTS ? g1 : gap(th);
      if (g >= 0.0) { hi = th; ghi = g; break; }
      lo = th; glo = g;
    }
    if (hi < 0.0) return -1.0;
    var side = 0;
    for (var it = 0; it < 200; it++) {
      if (hi - lo <= 4e-16 * hi) break;
      th = (lo * ghi - hi * glo) / (ghi - glo);
      if (!(lo < th && th < hi)) th = 0.5 * (lo + hi);
      g = gap(th);
      if (g >= 0.0) {
        hi = th; ghi = g;
        if (side === 1) glo *= 0.5;
        side = 1;
      } else {
        lo = th; glo = g;
        if (side === -1) ghi *= 0.5;
        side = -1;
      }
      if (g === 0.0) break;
    }
    return hi;
  }

  // ---------------------------------------------------------------- integration
  /** Integrate one contact from rest until the exit (Eq. 9), a budget or a failure
   * (driver.py ``integrate`` with method 1 and the 5(4) pair). */
  function integrate(p, opts, recorder) {
    var rest = restPosition(p.theta0);
    var reg = rest[1] !== 0.0;
    var rhs = makeRhs(p, reg);
    var rtol = opts.rtol, atol = opts.atol, maxSteps = opts.max_steps, tauMax = opts.tau_max;
    var x0 = rest[0], L0 = p.L0;
    var y = new Float64Array(N), f = new Float64Array(N), ynew = new Float64Array(N),
        fnew, err = new Float64Array(N), ys = new Float64Array(N);
    var K = [];
    for (var j = 0; j < 7; j++) K.push(new Float64Array(N));
    y[X] = rest[0]; y[Y] = rest[1]; y[THETA] = p.theta0;
    rhs(y, f);
    var h = initialStep(y, f, rhs, rtol, atol, ys, K[1]);
    var nAcc = 0, nRej = 0, nRhs = 2;
    if (recorder) recorder.add(0, false, y, f);
    var t = 0.0;
    var rMin = Math.sqrt(y[X] * y[X] + y[Y] * y[Y]), rMax = rMin;
    var lastRejected = false, logEnOld = LOG_EN_FLOOR, nonfinite = false, finishing = false;
    var status = -1, i, en, K0, K1, K2, K3, K4, K5, K6;
    while (status < 0) {
      if (nAcc + nRej >= maxSteps) { status = STEP_BUDGET; break; }
      if (y[TAU] >= tauMax) { status = TIME_BUDGET; break; }
      var hmin = 16.0 * EPS * Math.max(1.0, Math.abs(t));
      if (h < hmin) { status = nonfinite ? NONFINITE : STEP_UNDERFLOW; break; }
      // One Dormand-Prince 5(4) step (dopri5.py ``step``): stage arguments on the motion.
      K0 = K[0]; K1 = K[1]; K2 = K[2]; K3 = K[3]; K4 = K[4]; K5 = K[5]; K6 = K[6];
      for (i = 0; i < N; i++) K0[i] = f[i];
      for (i = 0; i < N_MOTION; i++) ys[i] = y[i] + h * A21 * K0[i];
      rhs(ys, K1);
      for (i = 0; i < N_MOTION; i++) ys[i] = y[i] + h * (A31 * K0[i] + A32 * K1[i]);
      rhs(ys, K2);
      for (i = 0; i < N_MOTION; i++) ys[i] = y[i] + h * (A41 * K0[i] + A42 * K1[i] + A43 * K2[i]);
      rhs(ys, K3);
      for (i = 0; i < N_MOTION; i++) {
        ys[i] = y[i] + h * (A51 * K0[i] + A52 * K1[i] + A53 * K2[i] + A54 * K3[i]);
      }
      rhs(ys, K4);
      for (i = 0; i < N_MOTION; i++) {
        ys[i] = y[i] + h * (A61 * K0[i] + A62 * K1[i] + A63 * K2[i] + A64 * K3[i] + A65 * K4[i]);
      }
      rhs(ys, K5);
      for (i = 0; i < N; i++) {
        ynew[i] = y[i] + h * (B1 * K0[i] + B3 * K2[i] + B4 * K3[i] + B5 * K4[i] + B6 * K5[i]);
      }
      rhs(ynew, K6);
      for (var k = 0; k < N_ERROR; k++) {
        i = ERROR_SLOTS[k];
        err[i] = h * (E1 * K0[i] + E3 * K2[i] + E4 * K3[i] + E5 * K4[i] + E6 * K5[i] + E7 * K6[i]);
      }
      nRhs += 6;
      en = errNorm(err, y, ynew, rtol, atol);
      if (en > 1.0 && !finishing) {
        nRej += 1;
        nonfinite = en === Infinity;
        h *= nonfinite ? 0.2 : Math.max(0.2, SAFETY * Math.exp(-EXPO * Math.log(en)));
        lastRejected = true;
        continue;
      }
      nonfinite = false;
      fnew = K6;  // f(ynew), the last stage (FSAL)
      if (finishing) {
        status = OK;
      } else {
        var th = -1.0;
        var g1 = ynew[TAU] - (ynew[X] - x0) - L0;
        if (g1 >= 0.0 || (y[VX] < 1.0 && ynew[VX] > 1.0)) th = locateExit(h, y, ynew, K, x0, L0);
        if (th > 0.0) {  // retake this step exactly to the located exit time
          h = th * h;
          finishing = true;
          continue;
        }
      }
      nAcc += 1;
      var rNew = Math.sqrt(ynew[X] * ynew[X] + ynew[Y] * ynew[Y]);
      var rIn = rInside(y, f, ynew, fnew, h);
      if (rIn >= 0.0) { rMin = Math.min(rMin, rIn); rMax = Math.max(rMax, rIn); }
      t += h;
      for (i = 0; i < N; i++) { y[i] = ynew[i]; f[i] = fnew[i]; }
      rMin = Math.min(rMin, rNew);
      rMax = Math.max(rMax, rNew);
      if (recorder) recorder.add(nAcc, false, y, f);
      var logEn = Math.log(Math.max(en, 1e-300)), fac;
      if (en === 0.0) fac = MAXFAC;
      else fac = Math.min(MAXFAC, Math.max(0.2, SAFETY * Math.exp(
        -(EXPO - 0.75 * PI_BETA) * logEn + PI_BETA * logEnOld)));
      logEnOld = Math.max(logEn, LOG_EN_FLOOR);
      if (lastRejected) fac = Math.min(1.0, fac);
      lastRejected = false;
      h *= fac;
    }
    if (recorder && nAcc % recorder.stride !== 0) recorder.add(nAcc, true, y, f);
    return {status: status, y: y, rMin: rMin, rMax: rMax,
            stats: {n_steps: nAcc, n_rejected: nRej, n_rhs: nRhs}};
  }


  return {integrate: integrate, hermite: hermite, OK: OK, STEP_BUDGET: STEP_BUDGET,
          TIME_BUDGET: TIME_BUDGET, STEP_UNDERFLOW: STEP_UNDERFLOW, NONFINITE: NONFINITE};
}));
