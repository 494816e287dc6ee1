#!/usr/bin/env node
/* Run the JavaScript kernel from Node: `node node_simulate.js < inputs.json > results.json`.
 *
 * Reads a JSON array of simulate() inputs ({k_r, k_theta, F_N, theta0, beta, rtol, ...})
 * from standard input and writes the JSON array of their results (the quantities of
 * `micropillar support --json`); an input that is refused gives {"error": "..."} in its
 * place. Used by the agreement tests and the benchmark (docs/offline.md).
 */
"use strict";
const kernel = require("./kernel.js");

require("./node_io.js")((input) => kernel.simulate(input));
