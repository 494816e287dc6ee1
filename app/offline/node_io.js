/* Node runners' input and output: a JSON array on standard input, each item mapped by
 * ``each`` (a refused item gives {"error": "..."} in its place), the JSON array of results
 * on standard output (Float64Arrays as plain arrays). Used by node_simulate.js and
 * node_arrays.js.
 */
"use strict";

module.exports = function mapStdin(each) {
  let text = "";
  process.stdin.setEncoding("utf8");
  process.stdin.on("data", (chunk) => { text += chunk; });
  process.stdin.on("end", () => {
    const results = JSON.parse(text).map((item) => {
      try {
        return each(item);
      } catch (error) {
        return {error: error.message};
      }
    });
    process.stdout.write(JSON.stringify(results, (key, value) =>
      (value instanceof Float64Array ? Array.from(value) : value)));
  });
};
