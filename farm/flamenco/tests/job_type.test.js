// Does the job type compile the commands and frame chunks a studio expects, for a few settings?
// SPDX-License-Identifier: GPL-3.0-or-later
"use strict";
const test = require("node:test");
const assert = require("node:assert/strict");
const path = require("node:path");
const {frameChunker, loadJobType} = require("./flamenco_standin.js");

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

test("the stand-in chunks frames as Flamenco does", () => {
    assert.deepEqual(frameChunker("1-10", 4), ["1-4", "5-8", "9-10"]);
    assert.deepEqual(frameChunker("3, 5-7, 9..10", 3), ["3,5-6", "7,9-10"]);
    assert.deepEqual(frameChunker("5", 10), ["5"]);
    assert.throws(() => frameChunker("", 3));
});

test("the job type declares its settings", () => {
    const {JOB_TYPE} = loadJobType(JOB_FILE);
    const keys = JOB_TYPE.settings.map((s) => s.key);
    for (const key of ["frames", "chunk_size", "render_output_path", "addon_module", "fail_on_pass_failure", "blendfile", "format", "scene"]) {
        assert.ok(keys.includes(key), `setting ${key}`);
    }
});

test("chunks of 4 over 1-10: three render tasks with Blender's frame notation", () => {
    const tasks = loadJobType(JOB_FILE).compile(settings());
    assert.deepEqual(tasks.map((t) => t.name), ["render-1-4", "render-5-8", "render-9-10"]);
    assert.deepEqual(tasks.map(frameArg), ["1..4", "5..8", "9..10"]);
    for (const t of tasks) {
        assert.equal(t.type, "blender");
        assert.equal(t.commands.length, 1);
        assert.equal(t.dependencies.length, 0, "chunks render independently");
    }
});

test("the exact command: add-on enabled, checked, failing with exit code 3", () => {
    const [task] = loadJobType(JOB_FILE).compile(settings({frames: "7", chunk_size: 1}));
    const command = task.commands[0];
    assert.equal(command.type, "blender-render");
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
    assert.deepEqual(tasks.map(frameArg), ["1..2", "3,10", "12..13"]);
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

test("refuses what cannot work", () => {
    const job = loadJobType(JOB_FILE);
    assert.throws(() => job.compile(settings({format: "FFMPEG"})), /renders images/);
    assert.throws(() => job.compile(settings({chunk_size: 0})), /chunk_size/);
    assert.throws(() => job.compile(settings({render_output_path: ""})), /render_output_path/);
});
