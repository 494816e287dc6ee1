/* The offline explorer's state in the URL fragment (docs/offline.md, "Links"):
 * ``#k_r=3&k_theta=0.01&F_N=1&theta0_deg=90&tab=polar&beta=0.5``.
 *
 *   parse(hash, config)  -> {state, notices}: the state a fragment asks for, and a notice
 *                           for every value it could not use (the default is kept);
 *   write(state, config) -> the fragment of a state.
 *
 * ``config`` is the page's configuration (app/offline/pack.py ``config()``: the controls'
 * ranges and defaults, the regimes, the tabs). The dashboard's links use the same keys
 * (app.urlstate), so a dashboard link's query is a fragment here: ``beta`` a number (a
 * fixed load factor) or ``self`` (solved, the default); a tab the page does not have
 * opens its closest (``config.closest_tabs``) with a notice saying what needs the
 * server. Works as a browser script (``MicropillarFragment``) and in Node.
 */
(function (root, factory) {
  "use strict";
  var api = factory();
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.MicropillarFragment = api;
}(typeof self !== "undefined" ? self : this, function () {
  "use strict";
  var KEYS = ["k_r", "k_theta", "F_N", "theta0_deg", "beta"];  // numbers (beta also "self")
  var FLAGS = ["projector", "play"];                            // 0 or 1

  function defaults(config) {
    var s = {tab: "support", projector: false, play: false, beta_mode: config.beta_mode.default};
    KEYS.forEach(function (k) { s[k] = config.controls[k].default; });
    return s;
  }

  function inRange(config, key, x) {
    var c = config.controls[key];
    return isFinite(x) && x >= c.lo && (c.hi_open ? x < c.hi : x <= c.hi);
  }

  function tabNotice(config, value) {
    var closest = config.closest_tabs[value];
    return "the " + value + " tab is not in the offline explorer (it needs the server): showing " +
      (closest ? closest.tab + " — " + closest.why : "the support");
  }

  function parse(hash, config) {
    var s = defaults(config), notices = [];
    var text = (hash || "").replace(/^#/, "");
    if (!text) return {state: s, notices: notices};
    var given = {};
    text.split("&").forEach(function (pair) {
      if (!pair) return;
      var i = pair.indexOf("="), key, value;
      try {
        key = decodeURIComponent(i < 0 ? pair : pair.slice(0, i));
        value = i < 0 ? "" : decodeURIComponent(pair.slice(i + 1).replace(/\+/g, " "));
      } catch (error) {
        notices.push("could not read “" + pair.slice(0, 40) + "” in the link: ignored");
        return;
      }
      given[key] = value;
    });
    if (given.regime !== undefined) {
      var regime = config.regimes[given.regime];
      if (regime) { s.k_r = regime.k_r; s.k_theta = regime.k_theta; }
      else notices.push("regime=" + given.regime.slice(0, 40) + " is not a regime (one of " +
                        Object.keys(config.regimes).join(", ") + "): kept the default springs");
    }
    Object.keys(given).forEach(function (key) {
      var value = given[key], c = config.controls[key];
      if (key === "regime") return;
      if (key === "beta" && value === "self") { s.beta_mode = "self"; return; }
      if (key === "beta") {  // a number: the fixed load factor (app.urlstate)
        var b = value.trim() === "" || value.length > 100 ? NaN : Number(value);
        if (inRange(config, key, b)) { s.beta = b; s.beta_mode = "fixed"; }
        else notices.push("beta=" + value.slice(0, 40) + " is not 'self' or " + c.expected +
                          ": using the self-consistent β");
        return;
      }
      if (KEYS.indexOf(key) >= 0) {
        var x = value.trim() === "" || value.length > 100 ? NaN : Number(value);
        if (inRange(config, key, x)) s[key] = x;
        else notices.push(key + "=" + value.slice(0, 40) + " is not " + c.expected +
                          ": using the default " + c.default);
      } else if (FLAGS.indexOf(key) >= 0) {
        if (value === "1" || value === "0") s[key] = value === "1";
        else notices.push(key + "=" + value.slice(0, 40) + " is not 0 or 1: ignored");
      } else if (key === "tab") {
        if (config.tabs.indexOf(value) < 0) {
          notices.push("tab=" + value.slice(0, 40) + " is not a tab (one of " + config.tabs.join(", ") +
                       "): showing the support");
        } else if (config.offline_tabs.indexOf(value) < 0) {
          notices.push(tabNotice(config, value));
          s.tab = config.closest_tabs[value] ? config.closest_tabs[value].tab : "support";
        } else s.tab = value;
      } else {
        notices.push(key.slice(0, 40) + " is not a setting of the offline explorer: ignored");
      }
    });
    return {state: s, notices: notices};
  }

  function write(s, config) {
    var parts = ["k_r", "k_theta", "F_N", "theta0_deg"].map(function (k) {
      return k + "=" + Number(s[k].toPrecision(6));
    });
    if (s.tab && s.tab !== "support" && config.offline_tabs.indexOf(s.tab) >= 0) parts.push("tab=" + s.tab);
    if (s.beta_mode === "fixed") parts.push("beta=" + Number(s.beta.toPrecision(6)));
    if (s.projector) parts.push("projector=1");
    return "#" + parts.join("&");
  }

  return {KEYS: KEYS, FLAGS: FLAGS, defaults: defaults, inRange: inRange, parse: parse, write: write};
}));
