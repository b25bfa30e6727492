// Does the job type compile the commands and frame chunks a studio expects, for a few settings?
// SPDX-License-Identifier: GPL-3.0-or-later
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const path = require("node:path");
const {frameChunker, jobTypeName, loadJobType} = require("./flamenco_standin.js");

const JOB_FILE = path.join(__dirname, "..", "softshadow-blender-render.js");

function settings(extra) {
    return {
        frames: "1-10", chunk_size: 4, render_output_root: "/render",
        render_output_path: "/render/shot/shot_######", fail_on_pass_failure: true,
        blendfile: "/projects/shot.blend", format: "PNG", scene: "Scene", ...extra,
    };
}

function frameArg(task) {
    const args = task.commands[0].parameters.args;
    return args[args.indexOf("--render-frame") + 1];
}

// What Flamenco 3.8.5's Manager compiled for these ranges (docs/user-guide.md#flamenco).
test("the stand-in chunks frames as Flamenco does", () => {
    assert.deepEqual(frameChunker("1-10", 4), ["1-4", "5-8", "9,10"]);
    assert.deepEqual(frameChunker("1-12", 5), ["1-5", "6-10", "11,12"]);
    assert.deepEqual(frameChunker("3, 5-7, 9..10", 3), ["3,5,6", "7,9,10"]);
    assert.deepEqual(frameChunker("5", 10), ["5"]);
    assert.deepEqual(frameChunker("4-2, 7", 3), ["7"], "a range ending before it starts adds nothing");
    assert.throws(() => frameChunker("", 3), /empty range/);
    assert.throws(() => frameChunker("4-2", 3), /empty range/);
    assert.throws(() => frameChunker("1,,2", 3), /invalid range/);
    assert.throws(() => frameChunker("-3", 3), /invalid range/);
    assert.throws(() => frameChunker("1-10", 0), /chunk size/);
});

test("the job type's name is its file name, as the Manager names it", () => {
    assert.equal(jobTypeName(JOB_FILE), "softshadow-blender-render");
    assert.equal(jobTypeName("/scripts/my_job_type.js"), "my-job-type");
});

test("the job type declares its settings", () => {
    const {JOB_TYPE} = loadJobType(JOB_FILE);
    const keys = JOB_TYPE.settings.map((s) => s.key);
    for (const key of ["frames", "chunk_size", "render_output_path", "addon_module", "passes_only",
        "task_per_light", "lights", "fail_on_pass_failure", "blendfile", "format", "scene"]) {
        assert.ok(keys.includes(key), `setting ${key}`);
    }
});

test("chunks of 4 over 1-10: three render tasks with Blender's frame notation", () => {
    const tasks = loadJobType(JOB_FILE).compile(settings());
    assert.deepEqual(tasks.map((t) => t.name), ["render-1-4", "render-5-8", "render-9,10"]);
    assert.deepEqual(tasks.map(frameArg), ["1..4", "5..8", "9,10"]);
    for (const t of tasks) {
        assert.equal(t.type, "blender");
        assert.equal(t.priority, 50);
        assert.equal(t.commands.length, 1);
        assert.equal(t.dependencies.length, 0, "chunks render independently");
    }
});

test("the exact command: add-on enabled, checked, failing with exit code 3", () => {
    const [task] = loadJobType(JOB_FILE).compile(settings({frames: "7", chunk_size: 1}));
    const command = task.commands[0];
    assert.equal(command.name, "blender-render");
    assert.equal(command.totalStepCount, 0);
    assert.equal(command.parameters.exe, "{blender}");
    assert.equal(command.parameters.exeArgs, "{blenderArgs}");
    assert.equal(command.parameters.blendfile, "/projects/shot.blend");
    assert.deepEqual(command.parameters.args, [
        "--scene", "Scene",
        "--python-exit-code", "3",
        "--addons", "softshadow",
        "--python-expr",
        "import bpy; assert hasattr(bpy.types.Scene, 'softshadow'), 'the softshadow add-on is not " +
            "installed or not enabled on this worker'; [setattr(s.softshadow, 'on_failure', 'STOP') for s in bpy.data.scenes]",
        "--render-output", "/render/shot/shot_######",
        "--render-format", "PNG",
        "--render-frame", "7",
    ]);
});

test("a frame list with gaps, one frame per task, and no forced failure policy", () => {
    const tasks = loadJobType(JOB_FILE).compile(settings({frames: "1-3, 10, 12-13", chunk_size: 2, fail_on_pass_failure: false, scene: ""}));
    assert.deepEqual(tasks.map(frameArg), ["1,2", "3,10", "12,13"]);
    const args = tasks[0].commands[0].parameters.args;
    assert.ok(!args.includes("--scene"), "no --scene without a scene name");
    const check = args[args.indexOf("--python-expr") + 1];
    assert.ok(!check.includes("on_failure"), "the file's own On Failure setting is kept");
});

test("the add-on's module for an extension install", () => {
    const [task] = loadJobType(JOB_FILE).compile(settings({frames: "1", addon_module: "bl_ext.user_default.softshadow"}));
    const args = task.commands[0].parameters.args;
    assert.equal(args[args.indexOf("--addons") + 1], "bl_ext.user_default.softshadow");
});

function passesSettings(extra) {
    return settings({frames: "1-6", chunk_size: 3, passes_only: true, lights: "Key\nRim light", ...extra});
}

function pythonExpr(task) {
    const args = task.commands[0].parameters.args;
    return args[args.indexOf("--python-expr") + 1];
}

test("passes only: chunked tasks that write the pass files and render nothing", () => {
    const tasks = loadJobType(JOB_FILE).compile(passesSettings());
    assert.deepEqual(tasks.map((t) => t.name), ["passes-1-3", "passes-4-6"]);
    const args = tasks[0].commands[0].parameters.args;
    assert.deepEqual(args, [
        "--scene", "Scene",
        "--python-exit-code", "3",
        "--addons", "softshadow",
        "--render-output", "/render/shot/shot_######",
        "--python-expr",
        "import bpy; assert hasattr(bpy.types.Scene, 'softshadow'), 'the softshadow add-on is not " +
            "installed or not enabled on this worker'; bpy.context.scene.softshadow.write_pass_files(\"1-3\")",
    ]);
    for (const t of tasks) {
        const a = t.commands[0].parameters.args;
        assert.ok(!a.includes("--render-frame") && !a.includes("-a") && !a.includes("-f"), "no frame renders");
        assert.ok(a.indexOf("--render-output") < a.indexOf("--python-expr"), "the pass files follow the render output");
    }
});

test("passes only, a task per light: every chunk once for each light, names quoted for Python", () => {
    const tasks = loadJobType(JOB_FILE).compile(passesSettings({task_per_light: true, lights: 'Key\n\nRim "A"\n'}));
    assert.deepEqual(tasks.map((t) => t.name), ["passes-1-3-Key", 'passes-1-3-Rim "A"', "passes-4-6-Key", 'passes-4-6-Rim "A"']);
    assert.ok(pythonExpr(tasks[0]).endsWith('write_pass_files("1-3", lights=["Key"])'), pythonExpr(tasks[0]));
    assert.ok(pythonExpr(tasks[3]).endsWith('write_pass_files("4-6", lights=["Rim \\"A\\""])'), pythonExpr(tasks[3]));
    for (const t of tasks) assert.equal(t.dependencies.length, 0, "the lights of a frame run side by side");
});

test("passes only does not care about the movie format; per-light tasks need lights and passes only", () => {
    const job = loadJobType(JOB_FILE);
    assert.equal(job.compile(passesSettings({format: "FFMPEG"})).length, 2);
    assert.throws(() => job.compile(passesSettings({task_per_light: true, lights: ""})), /names no light/);
    assert.throws(() => job.compile(settings({task_per_light: true})), /needs passes_only/);
});

test("refuses what cannot work", () => {
    const job = loadJobType(JOB_FILE);
    assert.throws(() => job.compile(settings({format: "FFMPEG"})), /renders images/);
    assert.throws(() => job.compile(settings({chunk_size: 0})), /chunk_size/);
    assert.throws(() => job.compile(settings({render_output_path: ""})), /render_output_path/);
});
