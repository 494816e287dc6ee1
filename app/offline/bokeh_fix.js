/* The one workaround in BokehJS of the offline page and of the served one (app/edge.py,
 * ``page_js``): a figure's paint rewrites its renderers' <style> elements even when their
 * text is unchanged.
 *
 * Each renderer (glyphs, axes, grids, the legend) writes its position into a <style> of its
 * own at every paint (``update_position`` -> ``InlineStyleSheet.replace`` -> ``_update``,
 * which sets ``textContent`` unconditionally). Each write invalidates the figure's styles,
 * and the next renderer's colours, read from CSS at paint time (``getComputedStyle``),
 * recalculate them: several style recalculations per figure and per paint
 * (docs/upstream/bokehjs_style_rewrite.py shows it in a plain Bokeh page). Here an
 * unchanged text is not written again; a changed one is, as before.
 *
 * Applied only to the BokehJS version it was tested with (``tested``, from the pack:
 * app.edge.TESTED) and only if the method it wraps is there; otherwise the page runs on
 * BokehJS's own behaviour and ``reason`` says why. tests/test_offline_fix.py checks the
 * guard (in Node); tests/browser/test_offline_fix.py fails the day the bug is fixed
 * upstream (the canary) and checks that a key press rewrites no <style> with its own text.
 *
 *   MicropillarBokehFix.apply(Bokeh, tested)  -> the same object: {applied, version, reason}
 *   MicropillarBokehFix.original              -> BokehJS's own _update, once applied
 */
(function (root) {
  "use strict";
  var fix = {applied: false, version: null, reason: "not applied yet", original: null};

  /** BokehJS's InlineStyleSheet prototype, or the reason it is not the one tested. */
  function target(bokeh, tested) {
    var version = bokeh ? bokeh.version : undefined;
    if (version !== tested) return {reason: "BokehJS " + version + " is not the tested " + tested};
    var dom = typeof bokeh.require === "function" ? bokeh.require("core/dom") : null;
    var proto = dom && dom.InlineStyleSheet && dom.InlineStyleSheet.prototype;
    if (!proto || typeof proto._update !== "function" || proto._update.length !== 1)
      return {reason: "BokehJS " + version + " has no InlineStyleSheet._update(css)"};
    return {proto: proto};
  }

  fix.apply = function (bokeh, tested) {
    if (fix.applied) return fix;
    var found = target(bokeh, tested);
    fix.version = bokeh ? bokeh.version : null;
    if (!found.proto) {
      fix.reason = found.reason;
      return fix;
    }
    var original = found.proto._update;
    found.proto._update = function (css) {
      if (this.el.textContent !== css) original.call(this, css);
    };
    fix.original = original;
    fix.applied = true;
    fix.reason = "";
    return fix;
  };
  root.MicropillarBokehFix = fix;
}(this));
