#!/usr/bin/env node
/* Run the JavaScript arrays from Node: `node node_arrays.js < calls.json > results.json`.
 *
 * Reads a JSON array of calls {fn, args}: fn one of "uniformArray", "fixedArray",
 * "orientationSweep" (app/offline/arrays.js), args its arguments; writes the JSON array of
 * their results (a refused call gives {"error": "..."}). Used by the agreement tests and
 * the benchmark (docs/offline.md).
 */
"use strict";
const arrays = require("./arrays.js");

let text = "";
process.stdin.setEncoding("utf8");
process.stdin.on("data", (chunk) => { text += chunk; });
process.stdin.on("end", () => {
  const results = JSON.parse(text).map((call) => {
    try {
      if (!Object.prototype.hasOwnProperty.call(arrays, call.fn) || typeof arrays[call.fn] !== "function") {
        throw new RangeError(`${call.fn} is not a function of arrays.js`);
      }
      const started = process.hrtime.bigint();
      const result = arrays[call.fn](...call.args);
      result.ms = Number(process.hrtime.bigint() - started) / 1e6;
      return result;
    } catch (error) {
      return {error: error.message};
    }
  });
  process.stdout.write(JSON.stringify(results, (key, value) =>
    (value instanceof Float64Array ? Array.from(value) : value)));
});
