// What a Flamenco 3 Manager runs to render a .blend with soft-shadow passes: chunked Blender
// render tasks with the softshadow add-on enabled, each failing when a frame's passes fail; or,
// passes only, chunked tasks that write the pass files without rendering (one per light if asked).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Install: copy this file into the Manager's `scripts/` folder (the Manager reads that folder
// again whenever job types are asked for: no restart); the job type "Blender Render with Soft
// Shadows" (named softshadow-blender-render after this file) appears in the Blender add-on's
// submission panel after its job types are refreshed. Each render task runs:
//   blender -b -y FILE.blend --python-exit-code 3 --addons ADDON_MODULE
//           --python-expr CHECK --render-output OUT --render-format FMT --render-frame A..B
// and each passes-only task:
//   blender -b -y FILE.blend --python-exit-code 3 --addons ADDON_MODULE --render-output OUT
//           --python-expr "CHECK; bpy.context.scene.softshadow.write_pass_files('A-B'[, lights=[...]])"
// Both exit non-zero when the add-on is missing on the worker (CHECK) or a frame's passes fail
// (the add-on exits 3 before that frame is rendered; write_pass_files raises): Flamenco then
// fails the task.

const JOB_TYPE = {
    label: "Blender Render with Soft Shadows",
    description: "Renders frames in chunks with the softshadow add-on's passes; a task fails when a frame's passes fail",
    settings: [
        {
            key: "frames", type: "string", required: true,
            eval: "f'{C.scene.frame_start}-{C.scene.frame_end}'",
            evalInfo: {showLinkButton: true, description: "Scene frame range"},
            description: "Frames to render, e.g. '47', '1-30', '3, 5-10, 47-327'",
        },
        {
            key: "chunk_size", type: "int32", default: 5, visible: "submission",
            description: "Number of frames one task renders (one Blender start per chunk)",
        },
        {
            key: "render_output_root", type: "string", subtype: "dir_path", required: true,
            visible: "submission",
            description: "Base folder of the render output; the soft-shadow passes go in a " +
                "'softshadow' folder beside the frames unless the file sets its own template",
        },
        {
            key: "render_output_path", type: "string", subtype: "file_path", editable: false,
            eval: "str(Path(abspath(settings.render_output_root), jobname, jobname + '_######'))",
            description: "Final file path of the frames; '#' become the frame number",
        },
        {
            key: "addon_module", type: "string", default: "softshadow", visible: "submission",
            description: "The add-on's module on the workers: 'softshadow' when installed as a " +
                "legacy add-on, 'bl_ext.<repository>.softshadow' as an extension (4.2+, e.g. " +
                "bl_ext.user_default.softshadow)",
        },
        {
            key: "passes_only", type: "bool", default: false, visible: "submission",
            description: "Write only the soft-shadow pass files of the frames, rendering nothing " +
                "(a compositor iterates on the shadows without re-rendering the frames)",
        },
        {
            key: "task_per_light", type: "bool", default: false, visible: "submission",
            description: "Passes only: one task per light and chunk, so Workers share a frame's " +
                "lights; each light's passes go in files of their own (its name before the frame number)",
        },
        {
            key: "lights", type: "string", visible: "web",
            eval: "'\\n'.join(o.name for o in C.scene.objects if o.type == 'LIGHT' and " +
                "getattr(getattr(o.data, 'softshadow', None), 'enabled', False))",
            description: "The lights whose passes are enabled, one name a line (for per-light tasks)",
        },
        {
            key: "fail_on_pass_failure", type: "bool", default: true, visible: "submission",
            description: "Fail the task when a frame's soft-shadow passes fail (sets every " +
                "scene's On Failure to Stop the Render)",
        },
        // Automatically evaluated settings:
        {key: "blendfile", type: "string", required: true, visible: "web", description: "Path of the Blend file to render"},
        {key: "format", type: "string", required: true, eval: "C.scene.render.image_settings.file_format", visible: "web"},
        {key: "scene", type: "string", required: false, eval: "C.scene.name", visible: "web",
         description: "Name of the scene to render"},
    ],
};

// Blender formats that hold one frame per file (the passes are per frame too).
const videoFormats = ["FFMPEG", "AVI_RAW", "AVI_JPEG"];

// Exit code of Blender when a --python-expr raises (the add-on's own failure code is also 3).
const EXIT_FAILED = 3;

function compileJob(job) {
    const settings = job.settings;
    if (!settings.passes_only && videoFormats.indexOf(settings.format) >= 0) {
        throw `This job type renders images, not "${settings.format}": the passes are per frame`;
    }
    if (!(settings.chunk_size >= 1)) {
        throw `chunk_size must be 1 or more, not ${settings.chunk_size}`;
    }
    const renderOutput = settings.render_output_path;
    if (!renderOutput) {
        throw "no render_output_path setting";
    }
    if (settings.task_per_light && !settings.passes_only) {
        throw "task_per_light needs passes_only: a render task renders all of a frame's lights";
    }
    const tasks = settings.passes_only ? authorPassesTasks(settings, renderOutput)
        : authorRenderTasks(settings, renderOutput);
    for (const task of tasks) {
        job.addTask(task);
    }
}

// The light names of the `lights` setting (one a line), for per-light tasks.
function lightNames(settings) {
    const names = String(settings.lights || "").split("\n").map((n) => n.trim()).filter((n) => n.length);
    if (names.length === 0) {
        throw "task_per_light: the lights setting names no light whose passes are enabled";
    }
    return names;
}

// The Python run on the worker first: the add-on must be registered.
const ADDON_CHECK = "import bpy; assert hasattr(bpy.types.Scene, 'softshadow'), " +
    "'the softshadow add-on is not installed or not enabled on this worker'";

// Before rendering: the add-on check, and (by default) every scene stops the render when a
// frame's passes fail.
function workerCheck(settings) {
    const lines = [ADDON_CHECK];
    if (settings.fail_on_pass_failure !== false) {
        lines.push("[setattr(s.softshadow, 'on_failure', 'STOP') for s in bpy.data.scenes]");
    }
    return lines.join("; ");
}

// One Blender run on the worker: the file, its scene, the add-on enabled, then `args`.
function blenderCommand(settings, args) {
    const sceneArgs = settings.scene ? ["--scene", settings.scene] : [];
    return author.Command("blender-render", {
        exe: "{blender}",
        exeArgs: "{blenderArgs}",
        argsBefore: [],
        blendfile: settings.blendfile,
        args: sceneArgs.concat([
            "--python-exit-code", String(EXIT_FAILED),
            "--addons", settings.addon_module || "softshadow",
        ], args),
    });
}

function authorRenderTasks(settings, renderOutput) {
    const tasks = [];
    for (const chunk of frameChunker(settings.frames, settings.chunk_size)) {
        const task = author.Task(`render-${chunk}`, "blender");
        task.addCommand(blenderCommand(settings, [
            "--python-expr", workerCheck(settings),
            "--render-output", renderOutput,
            "--render-format", settings.format,
            "--render-frame", chunk.replaceAll("-", ".."), // Blender's range notation
        ]));
        tasks.push(task);
    }
    return tasks;
}

// Passes only: the render output still decides where the pass files go (beside the frames,
// unless the file sets its own template); nothing renders, as no frame is asked of Blender.
// JSON string literals are Python string literals too.
function authorPassesTasks(settings, renderOutput) {
    const tasks = [];
    const lights = settings.task_per_light ? lightNames(settings) : [null];
    for (const chunk of frameChunker(settings.frames, settings.chunk_size)) {
        for (const light of lights) {
            const name = light === null ? `passes-${chunk}` : `passes-${chunk}-${light}`;
            const lightArg = light === null ? "" : `, lights=[${JSON.stringify(light)}]`;
            const task = author.Task(name, "blender");
            task.addCommand(blenderCommand(settings, [
                "--render-output", renderOutput,
                "--python-expr", ADDON_CHECK +
                    `; bpy.context.scene.softshadow.write_pass_files(${JSON.stringify(chunk)}${lightArg})`,
            ]));
            tasks.push(task);
        }
    }
    return tasks;
}
