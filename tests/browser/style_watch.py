"""Counting a page's rewrites of its <style> elements (BokehJS's paint,
``app/offline/bokeh_fix.js``), in the offline page and in the served one."""

#: Watches (anew) every <style> in the page and in its shadow roots (BokehJS's views have one
#: each); ``window.styleWrites`` counts rewrites with the same text and with another.
WATCH = """() => {
  (window.styleWatchers || []).forEach((o) => o.disconnect());
  window.styleWatchers = [];
  window.styleWrites = {same: 0, changed: 0};
  const seen = (records) => records.forEach((r) => {
    if (r.type !== "childList" || r.target.tagName !== "STYLE") return;
    const old = [...r.removedNodes].map((n) => n.textContent).join("");
    const now = [...r.addedNodes].map((n) => n.textContent).join("");
    window.styleWrites[old === now ? "same" : "changed"] += 1;
  });
  const watch = (root) => {
    const watcher = new MutationObserver(seen);
    watcher.observe(root, {childList: true, subtree: true});
    window.styleWatchers.push(watcher);
    root.querySelectorAll("*").forEach((el) => { if (el.shadowRoot) watch(el.shadowRoot); });
  };
  watch(document);
}"""
#: BokehJS's own method back (``own``) or the workaround again.
USE = """(own) => {
  const proto = Bokeh.require("core/dom").InlineStyleSheet.prototype;
  window.fixed = window.fixed || proto._update;
  proto._update = own ? MicropillarBokehFix.original : window.fixed;
}"""
