// What a Flamenco 3 Manager gives a job type's compileJob, as far as our job type uses it
// (author.Task, author.Command, task.addCommand, task.addDependency, job.addTask, frameChunker,
// frameCount, path, print), checked against a real Manager (Flamenco 3.8.5, docs/user-guide.md#flamenco).
// SPDX-License-Identifier: GPL-3.0-or-later
"use strict";
const fs = require("node:fs");
const path = require("node:path");
const vm = require("node:vm");

// "1-10, 20..25,40" -> sorted unique frames, as the Manager's frameRangeExplode: Blender's ".."
// becomes "-", each part is a frame or A-B (no negative frames, no empty part), and a range
// that ends before it starts adds no frame.
function explode(frameRange) {
    const frames = new Set();
    const number = (text, part) => {
        if (!/^\s*\+?\d+\s*$/.test(text)) throw new Error(`invalid range "${frameRange}": ${part}`);
        return Number(text);
    };
    for (const part of frameRange.replaceAll("..", "-").split(",")) {
        const ends = part.split("-");
        if (ends.length > 2) throw new Error(`invalid range "${frameRange}": ${part}`);
        const start = number(ends[0], part);
        const end = ends.length === 1 ? start : number(ends[1], part);
        for (let f = start; f <= end; f++) frames.add(f);
    }
    return [...frames].sort((a, b) => a - b);
}

// Consecutive frames merged as the Manager's frameRangeMerge does: three or more become "A-B",
// two stay two frames: [1,2,3,5,7,8] -> "1-3,5,7,8".
function merge(frames) {
    const parts = [];
    for (let i = 0; i < frames.length;) {
        let j = i;
        while (j + 1 < frames.length && frames[j + 1] === frames[j] + 1) j++;
        if (j - i >= 2) parts.push(`${frames[i]}-${frames[j]}`);
        else for (let k = i; k <= j; k++) parts.push(`${frames[k]}`);
        i = j + 1;
    }
    return parts.join(",");
}

// At most chunkSize frames per chunk, in "regular" notation (as Flamenco's frameChunker).
function frameChunker(frameRange, chunkSize) {
    if (!frameRange || !frameRange.trim()) throw new Error(`invalid range "${frameRange}": empty range`);
    if (!(chunkSize >= 1)) throw new Error(`invalid chunk size, must be positive number: ${chunkSize}`);
    const frames = explode(frameRange.trim());
    if (frames.length === 0) throw new Error(`invalid range "${frameRange}": empty range`);
    const chunks = [];
    for (let i = 0; i < frames.length; i += chunkSize) chunks.push(merge(frames.slice(i, i + chunkSize)));
    return chunks;
}

class Task {
    constructor(name, type) {
        this.name = name;
        this.type = type;
        this.priority = 50;
        this.commands = [];
        this.dependencies = [];
    }
    addCommand(command) { this.commands.push(command); }
    addDependency(task) { this.dependencies.push(task); }
}

// As the Manager's author module: names and types trimmed and required; a command is
// {name, parameters, totalStepCount} (its name is the command type the Worker runs).
const author = {
    Task: (name, type) => {
        name = String(name ?? "").trim();
        type = String(type ?? "").trim();
        if (!name) throw new Error("author.Task(name, type): name is required");
        if (!type) throw new Error("author.Task(name, type): type is required");
        return new Task(name, type);
    },
    Command: (name, parameters, totalStepCount) => ({name, parameters, totalStepCount: totalStepCount || 0}),
};

// The job type's name in the Manager: its file name without .js, "_" made "-".
function jobTypeName(file) {
    return path.basename(file, ".js").replaceAll("_", "-");
}

// Loads a job type file the way the Manager does (compiled as strict code, its top-level names
// global) and returns {name, JOB_TYPE, compile(settings) -> tasks}. The Manager passes the
// submitted settings as they are: no default of JOB_TYPE is filled in (the Blender add-on does).
function loadJobType(file) {
    const printed = [];
    const context = vm.createContext({
        author, frameChunker, path: path.posix, print: (...a) => printed.push(a.join(" ")),
        frameCount: (range) => explode(range).length,
        formatTimestampLocal: (d) => d.toISOString(),
    });
    const source = '"use strict";\n' + fs.readFileSync(file, "utf8") + "\n;this.JOB_TYPE = JOB_TYPE;";
    vm.runInContext(source, context, {filename: file, lineOffset: -1});
    return {
        name: jobTypeName(file),
        JOB_TYPE: context.JOB_TYPE,
        printed,
        compile(settings) {
            const job = {settings: {...settings}, created: new Date(0), tasks: [], addTask(t) { this.tasks.push(t); }};
            context.compileJob(job);
            // Plain data of this realm (dependencies by name), as the Manager stores the job.
            return JSON.parse(JSON.stringify(job.tasks.map((t) => ({
                name: t.name, type: t.type, priority: t.priority, commands: t.commands, dependencies: t.dependencies.map((d) => d.name),
            }))));
        },
    };
}

module.exports = {frameChunker, jobTypeName, loadJobType};
