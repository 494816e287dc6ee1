/* The offline page's order of drawing: what a key press changes first, the rest after.
 *
 * Bokeh lays a whole root out again whenever the text of a Div in it changes (tens to
 * hundreds of milliseconds with the figures in it), while new data in a figure's sources
 * only repaints that figure. So the page puts a new contact's data into the support's
 * figures at once and everything else -- texts, the polar diagrams' marker, the regime
 * map, the link -- "after the paint":
 *
 *   var later = new MicropillarPaint.Later(busy);
 *   later.put(key, fn);   // run fn after the next paint; a newer fn for the same key
 *                         // replaces it (the newest state wins, in order of first put)
 *   later.run();          // run what is waiting now (e.g. when nothing is computing)
 *   later.runBut(keys);   // run what is waiting now but ``keys`` (left for after the paint)
 *   later.waiting();      // true while work waits
 *
 * ``busy()`` true (a newer contact is being computed, e.g. keys held down) holds the
 * waiting work until the next ``put``/``run``: the reader sees the support move first.
 *
 *   var clock = new MicropillarPaint.KeyClock(window);
 *   clock.take();                 // at a state change: the key press that caused it, if any
 *   clock.drawn(key);             // after the support's data changed: records, at the
 *                                 // next animation frame, ms since that key press
 *   clock.times                   // the last 500 of those figures (the benchmark's)
 */
(function (root) {
  "use strict";
  var KEEP = 500;
  var HIDDEN_MS = 250;  // the latest a job waits for a frame (none come to a hidden page)

  function Later(busy) {
    this.busy = busy || function () { return false; };
    this.jobs = {}; this.order = []; this.scheduled = false;
  }
  Later.prototype.put = function (key, fn) {
    if (!(key in this.jobs)) this.order.push(key);
    this.jobs[key] = fn;
    this.schedule();
  };
  Later.prototype.schedule = function () {
    if (this.scheduled) return;
    this.scheduled = true;
    var self = this, fired = false;
    function fire() {
      if (fired) return;
      fired = true; self.scheduled = false; self.run();
    }
    // setTimeout inside the frame's callback: after that frame has been painted.
    root.requestAnimationFrame(function () { root.setTimeout(fire, 0); });
    root.setTimeout(fire, HIDDEN_MS);  // a hidden page gets no animation frames
  };
  /** True while work waits to be drawn. */
  Later.prototype.waiting = function () { return this.order.length > 0; };
  Later.prototype.run = function (force) {
    if (!force && this.busy()) return;  // the next put (the newer contact's) runs them
    var jobs = this.jobs, order = this.order;
    this.jobs = {}; this.order = [];
    order.forEach(function (key) { jobs[key](); });
  };

  Later.prototype.runBut = function (keys) {
    var jobs = this.jobs, order = this.order;
    this.order = order.filter(function (key) { return keys.indexOf(key) >= 0; });
    this.jobs = {};
    this.order.forEach(function (key) { this.jobs[key] = jobs[key]; }, this);
    order.forEach(function (key) { if (keys.indexOf(key) < 0) jobs[key](); });
  };

  function KeyClock(target) {
    var self = this;
    this.times = []; this.pressed = null; this.open = null;
    target.addEventListener("keydown", function (e) {
      // e.timeStamp: when the key was pressed (a busy page's wait is counted too)
      self.pressed = e.timeStamp;
      root.setTimeout(function () { self.pressed = null; }, 0);  // this press made no change
    }, true);
  }
  KeyClock.prototype.take = function () {
    if (this.pressed !== null && this.open === null) this.open = this.pressed;
    this.pressed = null;
  };
  KeyClock.prototype.drawn = function () {
    if (this.open === null) return;
    var at = this.open, times = this.times;
    this.open = null;
    root.requestAnimationFrame(function () {
      times.push(root.performance.now() - at);
      if (times.length > KEEP) times.shift();
    });
  };

  root.MicropillarPaint = {Later: Later, KeyClock: KeyClock};
}(this));
