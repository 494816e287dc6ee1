/* The offline page's texts: the headline (the dashboard's sentence,
 * app.views.readouts.headline_text, with F_T,x/(mu0 F_N), D_y/D_x and beta of the fixed
 * array beside the controls) and the uniform array's readout (the dashboard's table,
 * ``uniform_markdown``), from the kernel's and the arrays' results (views.js), and the
 * figures' descriptions for screen readers.
 *
 *   var texts = MicropillarReadouts(CONFIG, page);
 *       // page: {model(name), state() -> the page's state}
 *   texts.esc(text);                  // HTML-escaped
 *   texts.headline(result, felt, note);  // writes the headline's two Divs
 *   texts.uniform(u, ms);             // the uniform array's readout, as HTML
 *   texts.describe(figureName);       // a figure's description for screen readers
 */
(function (root) {
  "use strict";

  function esc(text) {
    return String(text).replace(/[&<>"]/g, function (c) {
      return {"&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;"}[c];
    });
  }

  /** A Markdown table (the dashboard's readouts) as HTML. */
  function tableHtml(markdown) {
    var parts = markdown.split("\n\n"), lines = parts[0].split("\n"), html = "<table class='mp-readout'>";
    lines.forEach(function (line, i) {
      if (i === 1) return;  // the alignment row
      var cells = line.replace(/^\|\s*|\s*\|$/g, "").split(/\s*\|\s*/), tag = i === 0 ? "th" : "td";
      html += "<tr>" + cells.map(function (c, j) {
        var bold = /^\*\*(.*)\*\*$/.exec(c), text = bold ? "<b>" + esc(bold[1]) + "</b>" : esc(c);
        return "<" + tag + (j ? " style='text-align:right'" : "") + ">" + text + "</" + tag + ">";
      }).join("") + "</tr>";
    });
    return html + "</table>" + (parts[1] ? "<p>" + esc(parts[1]) + "</p>" : "");
  }

  root.MicropillarReadouts = function (CONFIG, page) {
    var VIEWS = root.MicropillarViews;

    function betaWords(beta, note) {
      return "β = " + beta.toFixed(3) + (page.state().beta_mode === "fixed" ? " (fixed)" :
        " (self-consistent" + (note ? ": " + note : "") + ")");
    }

    /** The dashboard's sentence: the fixed array at theta0 and, once computed for this
     * state, the uniform array's average the slab feels (app.texts.FELT_AVERAGE): ``felt``
     * (null when not known) or ``note`` (why not). */
    function headline(r, felt, note) {
      var ratio = r.F_mean_x / CONFIG.mu0;
      var text = VIEWS.headlineText(ratio, Number(page.state().theta0_deg.toFixed(6)), felt,
                                     note, CONFIG.felt_words);
      page.model("headline").text = (r.success ? "" : "<span style='color:#b00020'>" +
                                     esc(r.message) + "</span><br>") + esc(text);
      page.model("headline-number").text = "F<sub>T,x</sub>/(μ<sub>0</sub>F<sub>N</sub>) = <b>" +
        ratio.toFixed(3) + "</b> <span style='font-size:0.85em'>(every support at θ₀, Eq. 10; " +
        "D<sub>y</sub>/D<sub>x</sub> = " + (r.D_y / r.D_x).toFixed(3) + "; " +
        betaWords(r.params.beta, r.beta_note) + ")</span>";
    }

    /** The uniform array's readout (its table, then beta, members, contacts, time). */
    function uniform(u, ms) {
      var row = null, extra = "";
      if (u.error || u.status === "budget") {
        extra = "<b>Not computed:</b> " + esc(u.error || u.message);
      } else {
        row = {FTx_over_mu0FN: u.FTx_over_mu0FN, FTx_over_mu0FN_duration: u.FTx_over_mu0FN_duration,
               Dy_over_Dx: u.Dy_over_Dx, Nc_over_Nc0: u.Nc_over_Nc0, success: u.success,
               quadrature_error_FTx: u.quadrature_error.FTx_over_mu0FN, n_failed: u.n_failed};
        extra = betaWords(u.beta, "") + "; " + u.n_members + " orientations, " +
          u.stats.trajectories + " contacts, computed in " + ms + " ms in the browser" +
          (u.message !== "ok" ? " — " + esc(u.message) : "");
      }
      return tableHtml(VIEWS.uniformMarkdown(
        row, CONFIG.felt_average, CONFIG.uniform_failed_note, CONFIG.average_names,
        CONFIG.average_columns, CONFIG.felt_average)) +
        "<div style='font-size:0.85em;color:#555555'>" + extra + "</div>";
    }

    /** A figure's description for screen readers (``nameFigures``,
     * app/figures/access_js.py): the state it shows, from the page's own texts (never per
     * animation frame). */
    function plain(html) {
      return String(html || "").replace(/<[^>]*>/g, "").replace(/\s+/g, " ").trim();
    }
    function springs() {
      var s = page.state(), K = root.MicropillarKernel;
      return "k_r = " + K.formatG(s.k_r, 3) + ", k_θ = " + K.formatG(s.k_theta, 3) +
        ", F_N = " + K.formatG(s.F_N, 3);
    }
    function describe(name) {
      if (/^polar_/.test(name))
        return "Fixed arrays against θ₀ for " + springs() + ": " +
          plain(page.model("polar-status").text);
      if (name === "regime_map")
        return plain(page.model("map-note").text).split(". Click")[0] + ". The current springs, " +
          springs() + ", are marked.";
      var text = plain(page.model("headline").text);
      if (!text) return null;
      return "One support, " + springs() + ", θ₀ = " + page.state().theta0_deg + "°: " + text;
    }

    return {esc: esc, headline: headline, uniform: uniform, describe: describe};
  };
}(this));
