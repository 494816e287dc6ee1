/* The offline page's tabs drawn when first shown (tabs.py's ``later_tab``): the
 * document holds a placeholder panel for each; the panel with its figures is in the JSON
 * element #mp-later, read and added to the document (BokehJS's
 * ``Document.apply_json_patch``) when the tab is first shown, so that the page opens with
 * the support tab's models alone.
 *
 *   var later = MicropillarLaterTabs(doc, tabs, keys);
 *       // tabs: the Tabs model; keys: each tab's key in order (CONFIG.offline_tabs)
 *   later.show(index);   // the tab's panel in place of its placeholder: true when it was
 *                        // added now, false when it was there already
 */
(function (root) {
  "use strict";
  var ELEMENT = "mp-later";

  root.MicropillarLaterTabs = function (doc, tabs, keys) {
    var panels = null;  // {key: the panel's JSON}, read at the first tab shown
    var built = {};

    function json() {
      if (panels === null) {
        var el = document.getElementById(ELEMENT);
        panels = el ? JSON.parse(el.textContent) : {};
      }
      return panels;
    }

    function show(index) {
      var key = keys[index];
      if (built[key]) return false;
      var panel = json()[key];
      if (!panel) { built[key] = true; return false; }  // in the document from the start
      // The new list of panels: the others by reference, this one in full.
      var list = tabs.tabs.map(function (p, k) { return k === index ? panel : {id: p.id}; });
      doc.apply_json_patch({events: [{kind: "ModelChanged", model: {id: tabs.id},
                                      attr: "tabs", new: list}]});
      built[key] = true;
      delete panels[key];
      return true;
    }

    return {show: show};
  };
}(this));
