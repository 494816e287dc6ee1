/* The offline page's first contact: requested as the page's scripts run, so that its
 * worker computes it while Bokeh reads its document; the document's views wait for it
 * (open.js), at most WAIT_MS, so that their first paint shows it.
 *
 *   var first = new MicropillarFirst(channel, input);  // requests it (jobs.js Channel)
 *   first.keep(result, ms, input);  // the channel's answer, before the document is there
 *   first.ready();        // a Promise, resolved once the contact is there or after WAIT_MS
 *   first.take(input);    // for the page's first state: [result, ms, input], or null when
 *                         // not there yet (the channel's answer is drawn when it comes);
 *                         // undefined for another input
 */
(function (root) {
  "use strict";
  var WAIT_MS = 250;

  root.MicropillarFirst = function (channel, input) {
    var key = JSON.stringify(input), got = null, done;
    var arrived = new Promise(function (resolve) { done = resolve; });
    channel.request(input);  // starts its worker with this job in its code

    return {
      keep: function (r, ms, inp) { got = [r, ms, inp]; done(); },
      ready: function () {
        return Promise.race([arrived, new Promise(function (resolve) {
          setTimeout(resolve, WAIT_MS);
        })]);
      },
      take: function (inp) { return JSON.stringify(inp) === key ? got : undefined; }
    };
  };
}(this));
