/* The offline page's job queues: each ``Channel`` runs one kind of job of arrays.js
 * (``MicropillarArrays.job``: "contact", "sweep", "uniform") in its own Web Worker, made
 * from the page's scripts kernel*.js, solvers.js and arrays.js, so the page never freezes.
 *
 *   var c = new MicropillarJobs.Channel(kind, draw(result, ms, input), busy(on));
 *   c.start(job);       // its worker (none in a browser without workers: then on the page)
 *   c.request(input);   // the newest request wins (starts the worker if not yet started,
 *                       // with this job in its code)
 *   c.runHere(input);   // a job known to be short: run now on the page's thread and drawn
 *                       // at once (no message, no frame between the key and the drawing);
 *                       // queued as ``request`` when a job runs or waits, or when the last
 *                       // one run here took over HERE_MS
 *   c.warmHere(input, n);  // run n times on the page's thread (V8 compiles and optimises
 *                       // the kernel there before the first ``runHere``); the last result
 *
 * One job at a time per channel; a newer request waits for the running job, or stops it
 * (the worker is replaced) when that job has run longer than RESTART_AFTER_MS: the reader
 * has moved on. A job's result is drawn only when no newer request is waiting.
 */
(function (root) {
  "use strict";
  var RESTART_AFTER_MS = 300;
  var HERE_MS = 30;  // the longest a job may hold the page's thread (runHere)
  var WORKER_SCRIPTS = ["mp-kernel_inputs", "mp-kernel_rhs", "mp-kernel_dopri5", "mp-kernel",
                        "mp-solvers", "mp-arrays"];
  var WORKER_CODE =
    "\nfunction run(job) {\n" +
    "  var t0 = Date.now(), r;\n" +
    "  try { r = MicropillarArrays.job(job.kind, job.input); }\n" +
    "  catch (error) { r = {error: error.message}; }\n" +
    "  self.postMessage({id: job.id, result: r, ms: Date.now() - t0});\n}\n" +
    "self.onmessage = function (e) { run(e.data); };\n";
  var nextId = 1;

  function Channel(kind, draw, busy) {
    this.kind = kind; this.draw = draw; this.busy = busy;
    this.worker = null; this.inFlight = null; this.pending = null; this.started = false;
    this.hereMs = 0;
  }

  /** A new worker; with ``job``, the worker runs it as soon as its scripts are read. A
   * message posted to a worker that is starting waits for the page's thread to pass it
   * on, and that thread may be busy for seconds (Bokeh building the document): a job in
   * the worker's own code does not wait for it. */
  Channel.prototype.start = function (job) {
    var self = this;
    this.started = true;
    try {
      var code = WORKER_SCRIPTS.map(function (id) {
        return document.getElementById(id).textContent;
      }).join("\n") + WORKER_CODE + (job ? "run(" + JSON.stringify(
        {id: job.id, kind: this.kind, input: job.input}) + ");\n" : "");
      var url = URL.createObjectURL(new Blob([code], {type: "text/javascript"}));
      var w = new Worker(url);
      URL.revokeObjectURL(url);
      w.onmessage = function (e) { self.finished(e.data.id, e.data.result, e.data.ms); };
      w.onerror = function () { self.worker = null; };
      this.worker = w;
      if (job) job.sent = true;
    } catch (error) {
      this.worker = null;  // no workers (an old browser): compute on the page, one job at a time
    }
  };

  Channel.prototype.request = function (input) {
    var job = {id: nextId++, input: input, started: Date.now(), sent: false};
    if (!this.started) this.start(job);
    if (this.inFlight) {
      this.pending = job;
      if (this.worker && Date.now() - this.inFlight.started > RESTART_AFTER_MS) {
        this.worker.terminate();  // a long computation the reader has moved on from
        this.start(job);
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
      if (!job.sent) this.worker.postMessage({id: job.id, kind: this.kind, input: job.input});
      return;
    }
    setTimeout(function () {
      var t0 = Date.now(), r = runOnPage(self.kind, job.input);
      self.finished(job.id, r, Date.now() - t0);
    }, 0);
  };

  function runOnPage(kind, input) {
    try { return root.MicropillarArrays.job(kind, input); }
    catch (error) { return {error: error.message}; }
  }
  Channel.prototype.runHere = function (input) {
    if (this.inFlight || this.pending || this.hereMs > HERE_MS) {
      if (!this.inFlight && !this.pending) this.hereMs = 0;  // the next one tries the page
      this.request(input);
      return;
    }
    var t0 = Date.now(), r = runOnPage(this.kind, input);
    this.hereMs = Date.now() - t0;
    this.draw(r, this.hereMs, input);
  };
  Channel.prototype.warmHere = function (input, n) {
    for (var i = 0, r; i < n; i++) r = runOnPage(this.kind, input);
    return r;
  };

  Channel.prototype.finished = function (id, result, ms) {
    if (!this.inFlight || this.inFlight.id !== id) return;  // an abandoned job
    var input = this.inFlight.input;
    this.inFlight = null;
    if (this.pending) { var next = this.pending; this.pending = null; this.send(next); return; }
    this.busy(false);
    this.draw(result, ms, input);
  };

  root.MicropillarJobs = {Channel: Channel, RESTART_AFTER_MS: RESTART_AFTER_MS, HERE_MS: HERE_MS};
}(this));
