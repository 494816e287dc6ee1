/* The offline page's polar diagrams (Fig. 11): an orientation sweep's F_T,x/(mu0 F_N),
 * F_T,y/(mu0 F_N) and D_y/D_x against theta0 (views.js ``polarData``), and the current
 * theta0's contact marked on them (``polarNow``). The diagrams are in the document once
 * their tab has been shown (tabs.js): until then the last sweep, contact and status are
 * kept, and drawn by ``show``.
 *
 *   var polar = MicropillarPolarView(CONFIG, page);
 *       // page: {setData({source: data}), setText(name, html), esc(text)}
 *   polar.draw(sweep, ms);   // a sweep (arrays.js ``orientationSweep``) into the diagrams;
 *                            // false for a sweep that failed (its error shown)
 *   polar.mark(result);      // the contact at theta0 (kernel.js ``simulate``) marked
 *   polar.status(html);      // the text under the diagrams
 *   polar.show();            // the diagrams are in the document now: draws what was kept
 */
(function (root) {
  "use strict";

  root.MicropillarPolarView = function (CONFIG, page) {
    var VIEWS = root.MicropillarViews;
    var axes = {};  // each diagram's axis scale (views.js), for its marker
    var shown = false, sweepNow = null, contactNow = null, text = null;

    function values(sweep, key) {
      return sweep.F_mean_x.map(function (_, i) {
        if (key === "FTx") return sweep.F_mean_x[i] / CONFIG.mu0;
        if (key === "FTy") return sweep.F_mean_y[i] / CONFIG.mu0;
        return sweep.D_y[i] / sweep.D_x[i];
      });
    }

    function status(html) {
      text = html;
      if (shown) page.setText("polar-status", html);
    }

    function paintSweep() {
      Object.keys(CONFIG.polar).forEach(function (key) {
        var res = VIEWS.polarData(key, CONFIG.polar[key][2], sweepNow.theta0, values(sweepNow, key));
        axes[key] = res[1];
        page.setData(res[0]);
      });
    }

    function paintMark() {
      var r = contactNow;
      var now = {FTx: r.F_mean_x / CONFIG.mu0, FTy: r.F_mean_y / CONFIG.mu0, DyDx: r.D_y / r.D_x};
      Object.keys(CONFIG.polar).forEach(function (key) {
        if (axes[key]) page.setData(VIEWS.polarNow(key, r.params.theta0, now[key], axes[key]));
      });
    }

    function draw(sweep, ms) {
      if (sweep.error) {
        status("<b>Not computed:</b> " + page.esc(sweep.error));
        return false;
      }
      sweepNow = sweep;
      if (shown) paintSweep();
      var failed = sweep.success.filter(function (ok) { return !ok; }).length;
      status(sweep.theta0.length + " orientations computed in " + ms +
        " ms in the browser" + (failed ? "; <b>" + failed + " contacts did not finish</b>" : ""));
      return true;
    }

    function mark(r) {
      contactNow = r;
      if (shown && sweepNow) paintMark();
    }

    function show() {
      shown = true;
      if (sweepNow) paintSweep();
      if (sweepNow && contactNow) paintMark();
      if (text !== null) page.setText("polar-status", text);
    }

    return {draw: draw, mark: mark, status: status, show: show};
  };
}(this));
