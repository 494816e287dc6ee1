#!/usr/bin/env node
/* Run the JavaScript arrays from Node: `node node_arrays.js < calls.json > results.json`.
 *
 * Reads a JSON array of calls {fn, args}: fn one of "uniformArray", "fixedArray",
 * "orientationSweep", "job" (app/offline/arrays.js), args its arguments; writes the JSON array of
 * their results, each with its time in ``ms`` (a refused call gives {"error": "..."}).
 * Used by the agreement tests (docs/offline.md).
 */
"use strict";
const arrays = require("./arrays.js");

require("./node_io.js")((call) => {
  if (!["uniformArray", "fixedArray", "orientationSweep", "job"].includes(call.fn)) {
    throw new RangeError(`${call.fn} is not a function of arrays.js`);
  }
  const started = process.hrtime.bigint();
  const result = arrays[call.fn](...call.args);
  result.ms = Number(process.hrtime.bigint() - started) / 1e6;
  return result;
});
