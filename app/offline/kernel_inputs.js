/* The inputs of one contact for the offline explorer's kernel (kernel.js): the model's
 * defaults and ranges (model.contact.params.DEFAULTS and RANGES, model.contact.options;
 * tests/test_offline_kernel.py checks they are the Python ones), their validation with
 * errors naming the value and the accepted range, and Python's "g" number format.
 *
 * Works as a browser script (``MicropillarKernelInputs``), in a Web Worker and in Node.
 */
(function (root, factory) {
  "use strict";
  var node = typeof module === "object" && module.exports;
  var api = factory();
  if (node) module.exports = api;
  else root.MicropillarKernelInputs = api;
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


  return {DEFAULTS: DEFAULTS, RANGES: RANGES, inputs: inputs, formatG: fmtG};
}));
