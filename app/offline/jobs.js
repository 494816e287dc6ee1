/* The offline page's job queues: each ``Channel`` runs one kind of job of arrays.js
 * (``MicropillarArrays.job``: "contact", "sweep", "uniform") in its own Web Worker, made
 * from the page's scripts kernel*.js, solvers.js and arrays.js, so the page never freezes.
 *
 *   var c = new MicropillarJobs.Channel(kind, draw(result, ms, input), busy(on));
 *   c.start();          // its worker (none in a browser without workers: then on the page)
 *   c.request(input);   // the newest request wins (starts the worker if not yet started)
 *
 * One job at a time per channel; a newer request waits for the running job, or stops it
 * (the worker is replaced) when that job has run longer than RESTART_AFTER_MS: the reader
 * has moved on. A job's result is drawn only when no newer request is waiting.
 */
(function (root) {
  "use strict";
  var RESTART_AFTER_MS = 300;
  var WORKER_SCRIPTS = ["mp-kernel_inputs", "mp-kernel_rhs", "mp-kernel_dopri5", "mp-kernel",
                        "mp-solvers", "mp-arrays"];
  var WORKER_CODE =
    "\nself.onmessage = function (e) {\n" +
    "  var t0 = Date.now(), r;\n" +
    "  try { r = MicropillarArrays.job(e.data.kind, e.data.input); }\n" +
    "  catch (error) { r = {error: error.message}; }\n" +
    "  self.postMessage({id: e.data.id, result: r, ms: Date.now() - t0});\n};\n";
  var nextId = 1;

  function Channel(kind, draw, busy) {
    this.kind = kind; this.draw = draw; this.busy = busy;
    this.worker = null; this.inFlight = null; this.pending = null; this.started = false;
  }

  Channel.prototype.start = function () {
    var self = this;
    this.started = true;
    try {
      var code = WORKER_SCRIPTS.map(function (id) {
        return document.getElementById(id).textContent;
      }).join("\n") + WORKER_CODE;
      var url = URL.createObjectURL(new Blob([code], {type: "text/javascript"}));
      var w = new Worker(url);
      URL.revokeObjectURL(url);
      w.onmessage = function (e) { self.finished(e.data.id, e.data.result, e.data.ms); };
      w.onerror = function () { self.worker = null; };
      this.worker = w;
    } catch (error) {
      this.worker = null;  // no workers (an old browser): compute on the page, one job at a time
    }
  };

  Channel.prototype.request = function (input) {
    if (!this.started) this.start();
    var job = {id: nextId++, input: input, started: Date.now()};
    if (this.inFlight) {
      this.pending = job;
      if (this.worker && Date.now() - this.inFlight.started > RESTART_AFTER_MS) {
        this.worker.terminate();  // a long computation the reader has moved on from
        this.start();
        this.inFlight = null;
        this.pending = null;
        this.send(job);
      }
      return;
    }
    this.send(job);
  };

  Channel.prototype.send = function (job) {
    var self = this;
    this.inFlight = job;
    this.busy(true);
    if (this.worker) {
      this.worker.postMessage({id: job.id, kind: this.kind, input: job.input});
      return;
    }
    setTimeout(function () {
      var t0 = Date.now(), r;
      try { r = root.MicropillarArrays.job(self.kind, job.input); }
      catch (error) { r = {error: error.message}; }
      self.finished(job.id, r, Date.now() - t0);
    }, 0);
  };

  Channel.prototype.finished = function (id, result, ms) {
    if (!this.inFlight || this.inFlight.id !== id) return;  // an abandoned job
    var input = this.inFlight.input;
    this.inFlight = null;
    if (this.pending) { var next = this.pending; this.pending = null; this.send(next); return; }
    this.busy(false);
    this.draw(result, ms, input);
  };

  root.MicropillarJobs = {Channel: Channel, RESTART_AFTER_MS: RESTART_AFTER_MS};
}(this));
