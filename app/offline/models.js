/* The offline page's Bokeh models, found by name in the page's document, and their look
 * (the screen's or the projector's, pack.py's styles).
 *
 * Figures and their sources share names (the dashboard's "forces", "polar_FTx"): a model
 * is found by its name and kind.
 *
 *   var m = MicropillarModels(doc);   // doc: window.Bokeh.documents[0]
 *   m.model("tabs");                  // a widget or any other model that is neither
 *   m.source("forces");               // a ColumnDataSource
 *   m.figure("forces");               // a figure
 *   m.setData({name: data, ...});     // new data for sources (repaints their figures only;
 *                                     // a source whose data are the same is left alone)
 *   m.range(fig, "x_range", [lo, hi]);  // redraws the figure, not its range's callbacks
 *   m.look(styles, on);               // projector mode on or off: ``styles`` the pack's
 *                                     // [model id, property, screen value, projector value]
 *   m.added(styles);                  // after models were added to the document (a tab
 *                                     // drawn when first shown, tabs.js): found by name,
 *                                     // and in the current look
 */
(function (root) {
  "use strict";

  function isSource(m) { return m.data !== undefined && m.selected !== undefined; }
  function isFigure(m) { return m.x_range !== undefined && m.renderers !== undefined; }
  /** True when ``data`` has the columns of ``now`` with the same values: setting it again
   * would have Bokeh re-render the glyphs (labels: their canvas layers) for nothing. */
  function same(now, data) {
    var keys = Object.keys(data);
    if (!now || keys.length !== Object.keys(now).length) return false;
    return keys.every(function (k) {
      var a = now[k], b = data[k];
      if (!a || !b || a.length !== b.length) return false;
      for (var i = 0; i < b.length; i++) if (a[i] !== b[i]) return false;
      return true;
    });
  }

  root.MicropillarModels = function (doc) {
    var byName = {}, known = {}, projectorShown = false;  // packed with the screen's look
    /** Indexes the document's models not seen yet; returns their ids ({id: true}). */
    function index() {
      var added = {};
      doc.all_models.forEach(function (m) {
        if (known[m.id]) return;
        known[m.id] = added[m.id] = true;
        if (m.name) (byName[m.name] = byName[m.name] || []).push(m);
      });
      return added;
    }
    index();
    function setStyle(c, on) {
      var m = doc.get_model_by_id(c[0]), attrs = {};
      if (!m) return;
      attrs[c[1]] = on ? c[3] : c[2];
      m.setv(attrs);
    }
    function find(name, test) {
      var list = byName[name] || [];
      for (var i = 0; i < list.length; i++) if (!test || test(list[i])) return list[i];
      throw new Error("the page has no model named " + name);
    }
    function source(name) { return find(name, isSource); }
    return {
      model: function (name) {
        return find(name, function (m) { return !isSource(m) && !isFigure(m); });
      },
      source: source,
      figure: function (name) { return find(name, isFigure); },
      setData: function (map) {
        Object.keys(map).forEach(function (k) {
          var src = source(k);
          if (!same(src.data, map[k])) src.data = map[k];
        });
      },
      range: function (fig, which, lohi) {
        // Set quietly, then one change (the plot and its axes redraw): not the callbacks on
        // its start and its end (the player's frame: drawn once the new contact is in).
        var r = fig[which];
        if (r.start === lohi[0] && r.end === lohi[1]) return;
        r.setv({start: lohi[0], end: lohi[1]}, {silent: true});
        r.change.emit();
      },
      look: function (styles, on) {
        if (on === projectorShown) return;  // (setting the same styles again repaints all)
        projectorShown = on;
        styles.forEach(function (c) { setStyle(c, on); });
        document.documentElement.classList.toggle("projector", on);
      },
      added: function (styles) {
        var added = index();  // (they were packed with the screen's look)
        if (projectorShown) styles.forEach(function (c) { if (added[c[0]]) setStyle(c, true); });
      }
    };
  };
}(this));
