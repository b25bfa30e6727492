// What a Flamenco 3 Manager runs to render a .blend with soft-shadow passes: chunked Blender
// render tasks with the softshadow add-on enabled, each failing when a frame's passes fail.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Install: copy this file into the Manager's `scripts/` folder and restart the Manager; the job
// type "Blender Render with Soft Shadows" appears in the Blender add-on's submission panel.
// Each task runs:
//   blender -b -y FILE.blend --python-exit-code 3 --addons ADDON_MODULE
//           --python-expr CHECK --render-output OUT --render-format FMT --render-frame A..B
// and exits non-zero when the add-on is missing on the worker (CHECK) or a frame's passes fail
// (the add-on exits 3 before that frame is rendered): Flamenco then fails the task.

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
    if (videoFormats.indexOf(settings.format) >= 0) {
        throw `This job type renders images, not "${settings.format}": the passes are per frame`;
    }
    if (!(settings.chunk_size >= 1)) {
        throw `chunk_size must be 1 or more, not ${settings.chunk_size}`;
    }
    const renderOutput = settings.render_output_path;
    if (!renderOutput) {
        throw "no render_output_path setting";
    }
    for (const task of authorRenderTasks(settings, renderOutput)) {
        job.addTask(task);
    }
}

// The Python run on the worker before rendering: the add-on must be registered, and (by default)
// every scene stops the render when a frame's passes fail.
function workerCheck(settings) {
    const lines = [
        "import bpy",
        "assert hasattr(bpy.types.Scene, 'softshadow'), 'the softshadow add-on is not installed or not enabled on this worker'",
    ];
    if (settings.fail_on_pass_failure !== false) {
        lines.push("[setattr(s.softshadow, 'on_failure', 'STOP') for s in bpy.data.scenes]");
    }
    return lines.join("; ");
}

function authorRenderTasks(settings, renderOutput) {
    const tasks = [];
    const chunks = frameChunker(settings.frames, settings.chunk_size);
    const sceneArgs = settings.scene ? ["--scene", settings.scene] : [];
    for (const chunk of chunks) {
        const task = author.Task(`render-${chunk}`, "blender");
        task.addCommand(author.Command("blender-render", {
            exe: "{blender}",
            exeArgs: "{blenderArgs}",
            argsBefore: [],
            blendfile: settings.blendfile,
            args: sceneArgs.concat([
                "--python-exit-code", String(EXIT_FAILED),
                "--addons", settings.addon_module || "softshadow",
                "--python-expr", workerCheck(settings),
                "--render-output", renderOutput,
                "--render-format", settings.format,
                "--render-frame", chunk.replaceAll("-", ".."), // Blender's range notation
            ]),
        }));
        tasks.push(task);
    }
    return tasks;
}
