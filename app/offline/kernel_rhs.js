/* The system the offline explorer's kernel (kernel.js) integrates: a port of
 * model/_kernel/rhs.py and slots.py. The 12-component state (motion, six quadratures,
 * tau), the friction law mu(v) of Eq. (4) (mu(s)/s by its Taylor series below zeta s =
 * 1e-3), the right-hand side of Eqs. (3)-(6) with the Sundman time regularisation near the
 * pivot, the rest position and the elastic energy of Eq. (12).
 *
 * Works as a browser script (``MicropillarKernelRhs``), in a Web Worker and in Node.
 */
(function (root, factory) {
  "use strict";
  var node = typeof module === "object" && module.exports;
  var api = factory(node ? require("./kernel_inputs.js") : root.MicropillarKernelInputs);
  if (node) module.exports = api;
  else root.MicropillarKernelRhs = api;
}(typeof self !== "undefined" ? self : this, function (I) {
  "use strict";
  var DEFAULTS = I.DEFAULTS;

  // State slots (model/_kernel/slots.py).
  var X = 0, Y = 1, VX = 2, VY = 3, THETA = 4, W = 5, I_Y = 6, D_X = 7, D_Y = 8,
      S_TH = 9, S_R = 10, TAU = 11;
  var N = 12, N_MOTION = 5;

  // Sundman regularisation (rhs.py).
  var R_S = 1e-6, DELTA = 1e-14;
  var SERIES_BELOW = 1e-3;

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


  /** The elastic energy U_el of Eq. (12) at (r, theta). */
  function elastic(p, r, theta) {
    var dth = theta - p.theta0;
    return 0.5 * p.k_r * (r - 1) * (r - 1) + 0.5 * p.k_theta * dth * dth +
           0.5 * (Math.exp(-r / p.lam) - Math.exp(-1.0 / p.lam));
  }


  return {X: X, Y: Y, VX: VX, VY: VY, THETA: THETA, W: W, I_Y: I_Y, D_X: D_X, D_Y: D_Y, S_TH: S_TH,
          S_R: S_R, TAU: TAU, N: N, N_MOTION: N_MOTION, SERIES_BELOW: SERIES_BELOW,
          restPosition: restPosition, seriesCoefficients: seriesCoefficients, mu: mu,
          makeRhs: makeRhs, elastic: elastic};
}));
