// Prints the tasks the job type compiles for the settings given as JSON (argv[2]): the Blender
// tests run these exact commands on a real .blend.
// SPDX-License-Identifier: GPL-3.0-or-later
"use strict";
const path = require("node:path");
const {loadJobType} = require("./flamenco_standin.js");

const job = loadJobType(path.join(__dirname, "..", "softshadow-blender-render.js"));
process.stdout.write(JSON.stringify(job.compile(JSON.parse(process.argv[2]))));
