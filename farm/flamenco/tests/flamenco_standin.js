// What a Flamenco 3 Manager gives a job type's compileJob, as far as our job type uses it: a
// stand-in written from Flamenco's job-compiler documentation (author.Task, author.Command,
// task.addCommand, task.addDependency, job.addTask, frameChunker, path, print).
// SPDX-License-Identifier: GPL-3.0-or-later
"use strict";
const fs = require("node:fs");
const path = require("node:path");
const vm = require("node:vm");

// "1-10, 20..25,40" -> sorted unique frames (Flamenco accepts "A-B" and Blender's "A..B").
function explode(frameRange) {
    const frames = new Set();
    for (const part of frameRange.split(",").map((p) => p.trim()).filter((p) => p.length)) {
        const m = /^(-?\d+)(?:(?:-|\.\.)(-?\d+))?$/.exec(part);
        if (!m) throw new Error(`invalid range "${frameRange}": cannot parse "${part}"`);
        const start = Number(m[1]);
        const end = m[2] === undefined ? start : Number(m[2]);
        if (end < start) throw new Error(`invalid range "${frameRange}": ${end} < ${start}`);
        for (let f = start; f <= end; f++) frames.add(f);
    }
    return [...frames].sort((a, b) => a - b);
}

// Consecutive frames merged into "A-B", the rest kept: [1,2,3,5] -> "1-3,5".
function merge(frames) {
    const parts = [];
    for (let i = 0; i < frames.length;) {
        let j = i;
        while (j + 1 < frames.length && frames[j + 1] === frames[j] + 1) j++;
        parts.push(i === j ? `${frames[i]}` : `${frames[i]}-${frames[j]}`);
        i = j + 1;
    }
    return parts.join(",");
}

// At most chunkSize frames per chunk, in "regular" notation (as Flamenco's frameChunker).
function frameChunker(frameRange, chunkSize) {
    if (!frameRange || !frameRange.trim()) throw new Error("invalid range: empty range");
    if (!(chunkSize >= 1)) throw new Error(`invalid chunk size, must be positive number: ${chunkSize}`);
    const frames = explode(frameRange);
    const chunks = [];
    for (let i = 0; i < frames.length; i += chunkSize) chunks.push(merge(frames.slice(i, i + chunkSize)));
    return chunks;
}

class Task {
    constructor(name, type) {
        this.name = name;
        this.type = type;
        this.commands = [];
        this.dependencies = [];
    }
    addCommand(command) { this.commands.push(command); }
    addDependency(task) { this.dependencies.push(task); }
}

const author = {
    Task: (name, type) => new Task(name, type),
    Command: (type, parameters) => ({type, parameters}),
};

// Loads a job type file the way the Manager does (its top-level names become globals) and
// returns {JOB_TYPE, compile(settings) -> tasks}.
function loadJobType(file) {
    const printed = [];
    const context = vm.createContext({
        author, frameChunker, path: path.posix, print: (...a) => printed.push(a.join(" ")),
        formatTimestampLocal: (d) => d.toISOString(),
    });
    vm.runInContext(fs.readFileSync(file, "utf8") + "\n;this.JOB_TYPE = JOB_TYPE;", context, {filename: file});
    return {
        JOB_TYPE: context.JOB_TYPE,
        printed,
        compile(settings) {
            const job = {settings: {...settings}, created: new Date(0), tasks: [], addTask(t) { this.tasks.push(t); }};
            context.compileJob(job);
            // Plain data of this realm (dependencies by name), as the Manager stores the job.
            return JSON.parse(JSON.stringify(job.tasks.map((t) => ({
                name: t.name, type: t.type, commands: t.commands, dependencies: t.dependencies.map((d) => d.name),
            }))));
        },
    };
}

module.exports = {frameChunker, loadJobType};
