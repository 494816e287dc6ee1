/* One support dragged by the slab, integrated in JavaScript: a port of the explicit
 * path of the Python kernel (model/_kernel: rhs.py, dopri5.py, driver.py, event.py,
 * batch.py) for the offline explorer (docs/offline.md).
 *
 * Same equations (Eqs. 3-6 of the paper, docs/model.md "One support"), same state
 * (motion, six quadratures, tau), same Sundman time regularisation near the pivot,
 * same Dormand-Prince 5(4) pair with its PI step-size control and its error norm over
 * the motion and tau, same exit condition (Eq. 9: first crossing of s(tau) = L0,
 * located on the 4th-order dense output and the step retaken to it), same derived
 * quantities (Eqs. 8, 12, 13). The Python kernel switches to DOP853 at rtol <= 1e-6 and
 * to Rodas4 where stiffness is detected; this port is the 5(4) pair alone, which is
 * what Python's ``method="explicit"`` uses at rtol > 1e-6 (tests/test_offline_kernel.py
 * checks it takes the very same steps there, and agrees with Python's default solver
 * at rtol 1e-8 on a grid of states).
 *
 * Works as a browser script (defines ``MicropillarKernel``), in a Web Worker and in
 * Node (``require``). No dependencies, no network, no allocation inside a step.
 */
(function (root, factory) {
  "use strict";
  var api = factory();
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.MicropillarKernel = api;
}(typeof self !== "undefined" ? self : this, function () {
  "use strict";

  // ---------------------------------------------------------------- constants
  // Friction law (Eq. 4), repulsion range (Eq. 3), slab length (Eq. 9): model.contact.params.DEFAULTS.
  var DEFAULTS = {mu_s: 1.3, A: 1.44, B: -20.0, zeta: 10.0, lam: 0.05, L0: 10.0};
  // What the model accepts: model.contact.params.RANGES and model.contact.options (checked by the tests).
  // [lo, hi, lo_open, hi_open, meaning]
  var TWO_PI = 2 * Math.PI;
  var RANGES = {
    k_r: [0, 1e6, true, false, "radial stiffness k_r"],
    k_theta: [0, 1e6, true, false, "torsional stiffness k_theta"],
    F_N: [0, 1e3, true, false, "normal load F_N"],
    theta0: [-TWO_PI, TWO_PI, false, false, "rest orientation theta0 [rad]"],
    beta: [1e-3, 1, false, false, "load factor beta = N_c0/N_c"],
    mu_s: [0, 100, true, false, "static friction coefficient mu_s"],
    A: [0, 100, true, false, "friction-law shape A"],
    B: [-1e4, 1e4, false, false, "friction-law shape B"],
    zeta: [0, 1e6, true, false, "friction-law velocity scale zeta = V0/V_s"],
    lam: [1e-4, 0.5, false, false, "repulsion range lambda"],
    L0: [0, 1e6, true, false, "slab length L0"],
    rtol: [1e-14, 1e-2, false, false, "relative tolerance rtol"],
    atol: [1e-16, 1e-2, false, false, "absolute tolerance atol"],
    tau_max: [1, 1e8, false, false, "time budget tau_max"]
  };
  var MAX_STEPS = [10, 1e8];
  var MAX_SAMPLES = 1e6;

  // State slots (model/_kernel/slots.py).
  var X = 0, Y = 1, VX = 2, VY = 3, THETA = 4, W = 5, I_Y = 6, D_X = 7, D_Y = 8,
      S_TH = 9, S_R = 10, TAU = 11;
  var N = 12, N_MOTION = 5;
  var ERROR_SLOTS = [X, Y, VX, VY, THETA, TAU];
  var N_ERROR = 6;
  // Status codes and texts (model.contact.results.Status).
  var OK = 0, STEP_BUDGET = 1, TIME_BUDGET = 2, STEP_UNDERFLOW = 3, NONFINITE = 4;
  var STATUS_TEXT = [
    ["contact ended: the slab slid L0 over the support (Eq. 9)", ""],
    ["step budget exhausted before the contact ended", "raise max_steps or loosen rtol"],
    ["time budget tau_max reached before the contact ended", "raise tau_max"],
    ["step size underflow", "try method='implicit' or a looser rtol"],
    ["non-finite state", "try method='implicit' or a looser rtol"]
  ];
  var ACCURACY_FACTOR = 3.0;            // model.contact.results.ACCURACY_FACTOR
  var PIVOT_RADIUS_OVER_LAMBDA = 0.2;   // model.arrays.contacts

  // Sundman regularisation (rhs.py).
  var R_S = 1e-6, DELTA = 1e-14;
  var SERIES_BELOW = 1e-3;
  // Step-size control (driver.py).
  var SAFETY = 0.9, PI_BETA = 0.04, LOG_EN_FLOOR = Math.log(1e-4), MAXFAC = 10.0;
  var ORDER = 5, EXPO = 1.0 / ORDER;
  var SCAN_POINTS = 8;
  var EPS = 2.220446049250313e-16;
  // Recorded nodes (record.py): at most MAX_NODES, then every other one.
  var MAX_NODES = 1 << 15;

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

  // ---------------------------------------------------------------- inputs
  function fmtG(x, precision) {
    // Python's format(x, ".<precision>g") (default 6): trailing zeros dropped.
    var P = precision || 6;
    if (x === 0) return "0";
    if (!isFinite(x)) return isNaN(x) ? "nan" : (x > 0 ? "inf" : "-inf");
    var parts = x.toExponential(P - 1).split("e");
    var exp = Number(parts[1]);
    if (exp < -4 || exp >= P) {
      var mant = parts[0].indexOf(".") >= 0 ? parts[0].replace(/\.?0+$/, "") : parts[0];
      return mant + "e" + (exp < 0 ? "-" : "+") + (Math.abs(exp) < 10 ? "0" : "") + Math.abs(exp);
    }
    var s = x.toFixed(Math.max(0, P - 1 - exp));
    return s.indexOf(".") >= 0 ? s.replace(/\.?0+$/, "") : s;
  }

  function interval(r) {
    return (r[2] ? "(" : "[") + fmtG(r[0]) + ", " + fmtG(r[1]) + (r[3] ? ")" : "]");
  }

  function number(name, value, fallback) {
    if (value === undefined || value === null) return fallback;
    var r = RANGES[name];
    var x = typeof value === "number" ? value : (typeof value === "string" && value.trim() !== ""
      ? Number(value) : NaN);
    if (isNaN(x) && !(typeof value === "number")) {
      throw new RangeError(name + "=" + JSON.stringify(value) + " is not a number; " + r[4] +
                           " must be a real number in " + interval(r));
    }
    var ok = isFinite(x) && (r[2] ? x > r[0] : x >= r[0]) && (r[3] ? x < r[1] : x <= r[1]);
    if (!ok) {
      throw new RangeError(name + "=" + String(value) + " is invalid: " + r[4] +
                           " must be finite and in " + interval(r));
    }
    return x;
  }

  function whole(name, value, lo, hi, fallback) {
    if (value === undefined || value === null) return fallback;
    var x = typeof value === "number" ? value : Number(value);
    if (!(isFinite(x) && Math.floor(x) === x && x >= lo && x <= hi)) {
      throw new RangeError(name + "=" + String(value) + " must be a whole number in [" +
                           fmtG(lo) + ", " + fmtG(hi) + "]");
    }
    return x;
  }

  var KNOWN = ["k_r", "k_theta", "F_N", "theta0", "beta", "mu_s", "A", "B", "zeta", "lam",
               "L0", "rtol", "atol", "max_steps", "tau_max", "samples"];

  /** Validated inputs with their defaults (model.contact.params.Params, model.contact.options). */
  function inputs(o) {
    if (o === null || typeof o !== "object") {
      throw new TypeError("simulate() takes one object: {k_r, k_theta, F_N, theta0, ...}");
    }
    for (var key in o) {
      if (Object.prototype.hasOwnProperty.call(o, key) && KNOWN.indexOf(key) < 0) {
        throw new RangeError(key + " is not an input of simulate(); known: " + KNOWN.join(", "));
      }
    }
    if (o.k_r === undefined || o.k_theta === undefined) {
      throw new RangeError("k_r and k_theta are required (e.g. {k_r: 3, k_theta: 0.01})");
    }
    var p = {
      k_r: number("k_r", o.k_r), k_theta: number("k_theta", o.k_theta),
      F_N: number("F_N", o.F_N, 1.0), theta0: number("theta0", o.theta0, Math.PI / 2),
      beta: number("beta", o.beta, 1.0)
    };
    for (var name in DEFAULTS) p[name] = number(name, o[name], DEFAULTS[name]);
    var rtol = number("rtol", o.rtol, 1e-6);
    var opts = {
      rtol: rtol, atol: number("atol", o.atol, rtol / 100),
      max_steps: whole("max_steps", o.max_steps, MAX_STEPS[0], MAX_STEPS[1], 1000000),
      tau_max: number("tau_max", o.tau_max, 1e5),
      samples: whole("samples", o.samples, 0, MAX_SAMPLES, 0)
    };
    return {params: p, options: opts};
  }

  /** (cos theta0, sin theta0), exactly on the x-axis at multiples of pi (model.contact.params). */
  function restPosition(theta0) {
    var x = Math.cos(theta0), y = Math.sin(theta0);
    // 4 * ulp(2 pi): the Python test |y| < 4 * math.ulp(2 * math.pi).
    if (Math.abs(y) < 4 * 8.881784197001252e-16) return [x < 0 ? -1.0 : 1.0, 0.0];
    return [x, y];
  }

  /** Taylor coefficients of mu(s)/(mu_s zeta) in z = zeta s (model.contact.friction). */
  function seriesCoefficients(A, B) {
    var A2 = A * A;
    var c2 = -A * (A2 + 2 * B + 2) / 6;
    var c4 = A * (A2 * A2 + 20 * A2 * B + 20 * A2 + 64 * B + 24) / 120;
    var c6 = -A * (A2 * A2 * A2 + 70 * A2 * A2 * B + 70 * A2 * A2 + 280 * A2 * B * B +
                   1904 * A2 * B + 784 * A2 + 560 * B * B + 3408 * B + 720) / 5040;
    return [A, c2, c4, c6];
  }

  /** mu(v) of Eq. (4). */
  function mu(v, p) {
    p = p || DEFAULTS;
    var z = p.zeta * v;
    return p.mu_s * Math.sin(p.A * Math.atan(z - p.B * (z - Math.atan(z))));
  }

  // ---------------------------------------------------------------- the system
  /** The right-hand side du/ds of the 12-component state (rhs.py ``_rhs``). */
  function makeRhs(p, reg) {
    var kr = p.k_r, kth = p.k_theta, fN = p.F_N * p.beta, th0 = p.theta0, lam = p.lam;
    var mus = p.mu_s, A = p.A, B = p.B, zeta = p.zeta;
    var c = seriesCoefficients(A, B), c0 = c[0], c2 = c[1], c4 = c[2], c6 = c[3];
    var RS2 = R_S * R_S, D2 = DELTA * DELTA;
    return function (u, out) {
      var x = u[0], y = u[1], vx = u[2], vy = u[3], dth = u[4] - th0;
      var r2 = x * x + y * y, r, q, pp, om;
      if (r2 > 0.0) {
        r = Math.sqrt(r2);
        var inv = 1.0 / r2;
        var g = -kr * (r - 1.0) + Math.exp(-r / lam) / (2.0 * lam);
        q = g * r * inv;
        pp = -kth * dth * inv;
        om = (x * vy - y * vx) * inv;
      } else {
        r = q = pp = om = 0.0;
      }
      var vrx = vx - 1.0;
      var s = Math.sqrt(vrx * vrx + vy * vy);
      var z = zeta * s, m;
      if (z < SERIES_BELOW) {
        var z2 = z * z;
        m = mus * zeta * (c0 + z2 * (c2 + z2 * (c4 + z2 * c6)));
      } else {
        var uu = z - B * (z - Math.atan(z));
        m = mus * Math.sin(A * Math.atan(uu)) / s;
      }
      var cf = -fN * m;
      var Fx = cf * vrx, Fy = cf * vy;
      var w = reg ? (r2 + D2) / (r2 + RS2) : 1.0;
      out[0] = w * vx;
      out[1] = w * vy;
      out[2] = w * (q * x - pp * y + Fx);
      out[3] = w * (q * y + pp * x + Fy);
      out[4] = w * om;
      out[5] = w * Fx;
      out[6] = w * Fy;
      out[7] = -w * Fx * vrx;
      out[8] = -w * Fy * vy;
      out[9] = w * dth * dth;
      out[10] = w * (r - 1.0) * (r - 1.0);
      out[11] = w;
    };
  }

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

  // ---------------------------------------------------------------- recording
  function Recorder() {
    this.rows = [];   // [tau, x, y, vx, vy, theta, W, D_x, D_y, then their d/dtau]
    this.stride = 1;
  }
  var REC = [X, Y, VX, VY, THETA, W, D_X, D_Y];
  Recorder.prototype.add = function (cand, force, y, f) {
    if (cand % this.stride !== 0 && !force) return;
    if (this.rows.length >= MAX_NODES) {
      var half = Math.floor((this.rows.length + 1) / 2);
      for (var i = 1; i < half; i++) this.rows[i] = this.rows[2 * i];
      this.rows.length = half;
      this.stride *= 2;
      if (cand % this.stride !== 0 && !force) return;
    }
    var row = new Float64Array(1 + 2 * REC.length);
    row[0] = y[TAU];
    for (var k = 0; k < REC.length; k++) {
      row[1 + k] = y[REC[k]];
      row[1 + REC.length + k] = f[REC[k]] / f[TAU];
    }
    this.rows.push(row);
  };

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

  // ---------------------------------------------------------------- results
  function elastic(p, r, theta) {
    var dth = theta - p.theta0;
    return 0.5 * p.k_r * (r - 1) * (r - 1) + 0.5 * p.k_theta * dth * dth +
           0.5 * (Math.exp(-r / p.lam) - Math.exp(-1.0 / p.lam));
  }

  function message(status, t, rMin, approach, pivotRadius, opts) {
    var text = STATUS_TEXT[status][0];
    if (status === OK) text += " at tau_out = " + fmtG(t);
    else if (status === STEP_BUDGET) text += " (max_steps = " + opts.max_steps + ", tau = " + fmtG(t) + ")";
    else if (status === TIME_BUDGET) text += " (tau_max = " + fmtG(opts.tau_max) + ")";
    else text += " at tau = " + fmtG(t);
    if (STATUS_TEXT[status][1]) text += "; " + STATUS_TEXT[status][1];
    if (approach) {
      text += "; the mass was driven into the region of its pivot (r_min = " +
              fmtG(rMin, 3) + " < " + fmtG(pivotRadius, 3) + ")";
    }
    return text;
  }

  /** Uniform samples of the histories: cubic Hermite through the recorded nodes
   * (model.contact.support ``_series_from_nodes``, ``_series``). */
  function series(p, rows, samples) {
    var kept = [], top = -Infinity;
    for (var i = 0; i < rows.length; i++) {
      if (i === 0 || rows[i][0] > top) kept.push(rows[i]);
      top = Math.max(top, rows[i][0]);
    }
    if (kept.length < 2 || samples < 1) return null;
    var nr = REC.length, tEnd = kept[kept.length - 1][0];
    var names = ["x", "y", "v_x", "v_y", "theta", "W", "D_x", "D_y"];
    var out = {tau: new Float64Array(samples)};
    names.forEach(function (n) { out[n] = new Float64Array(samples); });
    var seg = 0;
    for (var s = 0; s < samples; s++) {
      var tau = samples === 1 ? 0.0 : s * (tEnd / (samples - 1));
      if (s === samples - 1) tau = tEnd;
      while (seg < kept.length - 2 && tau > kept[seg + 1][0]) seg++;
      var a = kept[seg], b = kept[seg + 1], dt = b[0] - a[0], th = (tau - a[0]) / dt;
      out.tau[s] = tau;
      for (var k = 0; k < nr; k++) {
        out[names[k]][s] = hermite(a.subarray(1, 1 + nr), a.subarray(1 + nr),
                                   b.subarray(1, 1 + nr), b.subarray(1 + nr), dt, th, k);
      }
    }
    var n = samples, r = new Float64Array(n), Fx = new Float64Array(n), Fy = new Float64Array(n),
        Fa = new Float64Array(n), U = new Float64Array(n), Kin = new Float64Array(n);
    var c = seriesCoefficients(p.A, p.B);
    for (var m = 0; m < n; m++) {
      var vrx = out.v_x[m] - 1.0, vy = out.v_y[m], sp = Math.hypot(vrx, vy), z = p.zeta * sp, mo;
      if (z < SERIES_BELOW) {
        var z2 = z * z;
        mo = p.mu_s * p.zeta * (c[0] + z2 * (c[1] + z2 * (c[2] + z2 * c[3])));
      } else {
        mo = mu(sp, p) / sp;
      }
      Fx[m] = -mo * vrx; Fy[m] = -mo * vy; Fa[m] = Math.hypot(Fx[m], Fy[m]);
      r[m] = Math.hypot(out.x[m], out.y[m]);
      U[m] = elastic(p, r[m], out.theta[m]);
      Kin[m] = 0.5 * (out.v_x[m] * out.v_x[m] + vy * vy);
    }
    out.r = r; out.F_x = Fx; out.F_y = Fy; out.F_abs = Fa; out.U_el = U; out.K = Kin;
    return out;
  }

  /**
   * simulate({k_r, k_theta, F_N, theta0, beta, rtol, ...}): one contact, as
   * ``micropillar support --json`` reports it (the same names and meaning; docs/offline.md).
   */
  function simulate(o) {
    var io = inputs(o), p = io.params, opts = io.options;
    var rec = opts.samples > 0 ? new Recorder() : null;
    var run = integrate(p, opts, rec);
    var y = run.y, t = y[TAU], fN = p.F_N * p.beta;
    var r = Math.sqrt(y[X] * y[X] + y[Y] * y[Y]);
    var U = elastic(p, r, y[THETA]);
    var Kin = 0.5 * (y[VX] * y[VX] + y[VY] * y[VY]);
    var inv = t > 0.0 ? 1.0 / t : NaN;
    var rMin = Math.min(run.rMin, r), rMax = Math.max(run.rMax, r);
    var pivotRadius = PIVOT_RADIUS_OVER_LAMBDA * p.lam;
    var approach = rMin < pivotRadius;
    var residual = y[W] - (y[D_X] + y[D_Y] + U + Kin);
    var success = run.status === OK;
    var accurate = Math.abs(residual) / Math.max(Math.abs(y[W]), 1e-300) <=
                   ACCURACY_FACTOR * Math.max(opts.rtol, 1e-9);
    var msg = message(run.status, t, rMin, approach, pivotRadius, opts);
    if (success && !accurate) {
      msg += "; warning: the energy balance misses by " +
             (Math.abs(residual) / Math.max(Math.abs(y[W]), 1e-300)).toExponential(1).replace(/e([+-])(\d)$/, "e$10$2") +
             " of W, more than " + fmtG(ACCURACY_FACTOR) + " rtol: the result is inaccurate; tighten rtol";
    }
    var result = {
      t_out: t,
      state_out: [y[X], y[Y], y[VX], y[VY], y[THETA]],
      F_mean_x: y[W] * inv / fN,
      F_mean_y: y[I_Y] * inv / fN,
      W: y[W], D_x: y[D_X], D_y: y[D_Y], U_el: U, K: Kin,
      energy_residual: residual,
      dtheta_rms: Math.sqrt(Math.max(y[S_TH], 0.0) * inv),
      dr_rms: Math.sqrt(Math.max(y[S_R], 0.0) * inv),
      r_min: rMin, r_max: rMax, pivot_approach: approach, accurate: accurate,
      success: success, status: run.status, message: msg,
      stats: {n_steps: run.stats.n_steps, n_rejected: run.stats.n_rejected,
              n_rhs: run.stats.n_rhs, method: "explicit (Dormand-Prince 5(4), JavaScript)"},
      params: {k_r: p.k_r, k_theta: p.k_theta, F_N: p.F_N, theta0: p.theta0, beta: p.beta,
               mu_s: p.mu_s, A: p.A, B: p.B, zeta: p.zeta, lam: p.lam, L0: p.L0}
    };
    if (rec) result.series = series(p, rec.rows, opts.samples);
    return result;
  }

  return {
    simulate: simulate,
    mu: mu,
    mu0: function (p) { return mu(1.0, p || DEFAULTS); },
    restPosition: restPosition,
    DEFAULTS: DEFAULTS,
    RANGES: RANGES,
    STATUS_TEXT: STATUS_TEXT,
    ACCURACY_FACTOR: ACCURACY_FACTOR,
    formatG: fmtG
  };
}));
