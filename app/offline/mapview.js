/* The offline page's regime map (Fig. 5): the maps shipped with the model, at the shipped
 * load nearest to F_N, the current springs marked; a click or the arrow keys on the map's
 * tab set k_r and k_theta.
 *
 *   var map = MicropillarMapView(CONFIG, page);
 *       // page: {source(name), model(name), figure(name), clampRound(key, v),
 *       //        state() -> the page's state, set(partial) -> change it}
 *   map.draw();          // for the current state: new data only for a new load, quantity
 *                        // or springs; nothing until the map is in the document
 *   map.show();          // the map is in the document now (its tab shown, tabs.js): drawn
 *   map.quantity("5b");  // the quantity shown (the map's select)
 *   map.tap(x, y);       // a click at (k_r, k_theta)
 *   map.keys(event);     // a keydown: the arrow keys move one cell of the 24 x 24 grid
 */
(function (root) {
  "use strict";

  root.MicropillarMapView = function (CONFIG, page) {
    var K = root.MicropillarKernel, CONTROLS = CONFIG.controls;
    var shown = null, now = null, which = "5a";  // load/quantity shown, the springs marked
    var built = false;  // the map is in the document

    function nearestLoad(F) {
      var best = null;
      CONFIG.shipped_loads.forEach(function (L) {
        if (best === null || Math.abs(Math.log(L / F)) < Math.abs(Math.log(best / F))) best = L;
      });
      return best;
    }
    function loadLabel(L) { return K.formatG(L); }

    function draw() {
      if (!built) return;
      var state = page.state(), load = nearestLoad(state.F_N), m = CONFIG.maps.loads[loadLabel(load)];
      if (shown !== loadLabel(load) + "/" + which) {
        var data = Object.assign({}, CONFIG.maps.cells, m.columns);
        data.value = m.columns[CONFIG.maps.value[which]];
        page.source("regime_map").data = data;
        var lohi = m.range[which];
        page.model("regime_map_colors").setv({low: lohi[0], high: lohi[1]});
        page.figure("regime_map").title.text = m.titles[which];  // app.figures.arrays.map_title
        shown = loadLabel(load) + "/" + which;
      }
      page.model("map-note").text = "Uniform arrays (θ₀ uniform), self-consistent β, shipped " +
        "with the model at F_N = " + CONFIG.shipped_loads.map(loadLabel).join(", ") +
        ". Shown: F_N = " + loadLabel(load) + (Math.abs(load - state.F_N) > 1e-12 * load
          ? ", the shipped load nearest to the current F_N = " + K.formatG(state.F_N, 3) : "") +
        ". Click the map, or use the arrow keys on this tab (← → k_r, ↑ ↓ k_θ, one cell), " +
        "to set the springs.";
      if (now !== state.k_r + "," + state.k_theta) {
        page.source("regime_now").data = {k_r: [state.k_r], k_theta: [state.k_theta]};
        now = state.k_r + "," + state.k_theta;
      }
      document.documentElement.setAttribute("data-map", loadLabel(load) + "/" + which);
    }

    function tap(x, y) {
      if (!isFinite(x) || !isFinite(y)) return;
      page.set({k_r: page.clampRound("k_r", x), k_theta: page.clampRound("k_theta", y)});
    }

    /** Arrow keys on the map tab move the springs one cell of the shipped map's grid. */
    function keys(e) {
      var state = page.state();
      if (state.tab !== "map" || e.altKey || e.ctrlKey || e.metaKey) return;
      var tag = (e.target && e.target.tagName) || "";
      if (["INPUT", "SELECT", "TEXTAREA", "BUTTON"].indexOf(tag) >= 0) return;
      var path = e.composedPath ? e.composedPath() : [];
      if (path.some(function (el) {
        return el && el.getAttribute && (el.getAttribute("role") === "slider" ||
          el.getAttribute("role") === "tab" || (el.classList && el.classList.contains("noUi-handle")));
      })) return;
      var moves = {ArrowLeft: ["k_r", -1], ArrowRight: ["k_r", 1], ArrowDown: ["k_theta", -1],
                   ArrowUp: ["k_theta", 1]};
      var move = moves[e.key];
      if (!move) return;
      var k = CONFIG.maps.cells.k_r, n = Math.round(Math.sqrt(k.length));
      var step = Math.pow(CONTROLS.k_r.hi / CONTROLS.k_r.lo, 1 / (n - 1)), partial = {};
      partial[move[0]] = page.clampRound(move[0], state[move[0]] * Math.pow(step, move[1]));
      e.preventDefault();
      e.stopPropagation();  // not the player's keys: it is on another tab
      page.set(partial);
    }

    return {draw: draw, tap: tap, keys: keys,
            show: function () { built = true; draw(); },
            quantity: function (q) { which = q; draw(); }};
  };
}(this));
