// Flamenco job type "banyan-batch": N seeds of one banyan preset, split into
// tasks of K seeds; each task runs banyan's batch runner on a Worker (through
// Blender when it renders). Copy this file into the `scripts/` folder beside
// flamenco-manager; docs/batch.md ("Flamenco") is the guide.
//
// The runner (blender_addon/banyan/batch_run.py) is idempotent and writes every
// file by rename, so a task that a killed Worker leaves half done is simply run
// again; outputs are named from (preset hash, seed), so tasks never collide.
//
// Needs Flamenco 3.5 or later (Manager and Workers): before 3.5 the
// "blender-render" command refuses an empty blendfile. Written for Flamenco
// 3's job compiler (goja: ES2015+, no modules). Globals it uses: author.Task,
// author.Command, print. A task that renders runs "blender-render" with an
// empty blendfile, which the Worker runs as {blender} {blenderArgs}
// argsBefore args (the runner builds its scene). A task that only writes glTF
// needs no Blender: it runs the runner with Python 3 through "exec" (task type
// "misc"), which saves a Blender start per task; set `python` empty only for
// Workers without Python 3 (every task then starts Blender).
//
// Limits: at most MAX_TASKS seed tasks per job (raise seeds_per_task for
// more seeds) and at most SEEDS_MAX seeds (the runner's cap per merge).

const JOB_TYPE = {
    label: "banyan batch",
    description: "Generate N seeds of a banyan preset (.glb each, optional renders), K seeds per task",
    settings: [
        { key: "preset", type: "string", required: true, default: "avenue_batch_tiny",
          description: "Preset name, or path of a preset .json that every Worker can read" },
        { key: "first_seed", type: "int32", default: 0, propargs: { min: 0 },
          description: "First seed" },
        { key: "seed_count", type: "int32", required: true, default: 40, propargs: { min: 1 },
          description: "Number of seeds: first_seed .. first_seed + seed_count - 1" },
        { key: "seeds_per_task", type: "int32", default: 5, propargs: { min: 1 },
          description: "Seeds per task (K): one process start and library load per task" },
        { key: "output_dir", type: "string", subtype: "dir_path", required: true,
          default: "{jobs}/banyan-batch",
          description: "Output folder on shared storage, as the Workers see it ({jobs} is the shared storage path)" },
        { key: "render_seeds", type: "string", default: "",
          description: "Seeds to render as A:B (half-open), empty for none" },
        { key: "size", type: "int32", default: 64, propargs: { min: 16, max: 4096 },
          description: "Render width and height in pixels" },
        { key: "engine", type: "string", default: "WORKBENCH", choices: ["WORKBENCH", "EEVEE"],
          description: "Render engine" },
        { key: "textures", type: "bool", default: true,
          description: "Bark and leaf textures in the .glb (off: --no-textures)" },
        { key: "texture_size", type: "int32", default: 1024, propargs: { min: 64, max: 8192 },
          description: "glTF texture size, a power of two" },
        { key: "format", type: "string", default: "glb", choices: ["glb", "usda"],
          description: "glb (glTF binary) or usda (a USD text layer a seed, its textures shared)" },
        { key: "threads", type: "int32", default: 1, propargs: { min: 0, max: 1024 },
          description: "Generator threads per task (0: all cores); the bytes do not depend on it" },
        { key: "merge_manifest", type: "bool", default: true,
          description: "Last task: gather the per-seed records into <output_dir>/manifest.json, re-hashing every file" },
        { key: "python", type: "string", default: "python3", visible: "web",
          description: "Python 3 on the Workers for tasks that render nothing (no Blender start); empty: Blender for every task" },
        { key: "runner", type: "string", default: "{banyan}/batch_run.py", visible: "web",
          description: "batch_run.py as the Workers see it; define the Manager variable 'banyan' as the add-on folder" },
    ],
};

// Seeds are unsigned 32-bit in libbanyan; the end of a half-open range may be 2^32.
const SEED_END_MAX = 4294967296;
// A job of more tasks than this is refused: the Manager stores and schedules
// every task, and a huge count is nearly always a seeds_per_task left small.
const MAX_TASKS = 10000;
// The runner refuses a merge (and a run) of more seeds (batch_merge.SEEDS_MAX).
const SEEDS_MAX = 10000000;

function settingOf(job, key) {
    const v = job.settings[key];
    if (v !== undefined && v !== null) return v;
    for (const s of JOB_TYPE.settings) {
        if (s.key === key) return s.default;
    }
    return undefined;
}

function intSetting(job, key, min, max) {
    const v = settingOf(job, key);
    if (typeof v !== "number" || !Number.isInteger(v) || v < min || v > max) {
        throw `banyan-batch: setting ${key} must be an integer in [${min}, ${max}], got ${JSON.stringify(v)}`;
    }
    return v;
}

function stringSetting(job, key) {
    const v = settingOf(job, key);
    if (typeof v !== "string" || v.trim() === "") {
        throw `banyan-batch: setting ${key} must be a non-empty string, got ${JSON.stringify(v)}`;
    }
    return v.trim();
}

// "A:B" -> [A, B] (half-open, A < B); "" -> null.
function parseRange(key, text) {
    if (text === undefined || text === null || String(text).trim() === "") return null;
    const m = /^\s*(\d+)\s*:\s*(\d+)\s*$/.exec(String(text));
    const a = m ? Number(m[1]) : NaN, b = m ? Number(m[2]) : NaN;
    if (!m || !(a < b) || b > SEED_END_MAX) {
        throw `banyan-batch: setting ${key} must be A:B with 0 <= A < B <= ${SEED_END_MAX}, got ${JSON.stringify(text)}`;
    }
    return [a, b];
}

function compileJob(job) {
    const preset = stringSetting(job, "preset");
    const first = intSetting(job, "first_seed", 0, SEED_END_MAX - 1);
    const count = intSetting(job, "seed_count", 1, SEED_END_MAX - first);
    const perTask = intSetting(job, "seeds_per_task", 1, SEED_END_MAX);
    const outDir = stringSetting(job, "output_dir");
    const size = intSetting(job, "size", 16, 4096);
    const threads = intSetting(job, "threads", 0, 1024);
    const textureSize = intSetting(job, "texture_size", 64, 8192);
    if ((textureSize & (textureSize - 1)) !== 0) {
        throw `banyan-batch: setting texture_size must be a power of two in [64, 8192], got ${textureSize}`;
    }
    const textures = settingOf(job, "textures");
    if (typeof textures !== "boolean") {
        throw `banyan-batch: setting textures must be true or false, got ${JSON.stringify(textures)}`;
    }
    const merge = settingOf(job, "merge_manifest");
    if (typeof merge !== "boolean") {
        throw `banyan-batch: setting merge_manifest must be true or false, got ${JSON.stringify(merge)}`;
    }
    const runner = stringSetting(job, "runner");
    const pythonSetting = settingOf(job, "python");
    if (typeof pythonSetting !== "string") {
        throw `banyan-batch: setting python must be a string (empty: Blender for every task), got ${JSON.stringify(pythonSetting)}`;
    }
    const python = pythonSetting.trim();
    const format = stringSetting(job, "format");
    if (format !== "glb" && format !== "usda") {
        throw `banyan-batch: setting format must be glb or usda, got ${JSON.stringify(format)}`;
    }
    const engine = stringSetting(job, "engine").toUpperCase();
    if (engine !== "WORKBENCH" && engine !== "EEVEE") {
        throw `banyan-batch: setting engine must be WORKBENCH or EEVEE, got ${JSON.stringify(engine)}`;
    }
    const render = parseRange("render_seeds", settingOf(job, "render_seeds"));
    if (count > SEEDS_MAX) {
        throw `banyan-batch: setting seed_count ${count} is more than ${SEEDS_MAX} seeds, the runner's limit per ` +
            `merge: split the seeds into several jobs`;
    }
    const taskCount = Math.ceil(count / perTask);
    if (taskCount > MAX_TASKS) {
        throw `banyan-batch: setting seeds_per_task ${perTask} makes ${taskCount} tasks of seed_count ${count}, ` +
            `more than ${MAX_TASKS}: raise seeds_per_task to at least ${Math.ceil(count / MAX_TASKS)}`;
    }

    const end = first + count;
    const seedTasks = [];
    print(`banyan-batch: seeds ${first}:${end} of ${preset}, ${perTask} per task, into ${outDir}`);
    for (let a = first; a < end; a += perTask) {
        const b = Math.min(a + perTask, end);
        const args = [
            "--preset", preset,
            "--seeds", `${a}:${b}`,
            "--out", outDir,
        ];
        // Hand each task only its own share of the render range, so that what
        // it renders never depends on how the runner reads a wider range.
        let renders = false;
        if (render) {
            const ra = Math.max(a, render[0]), rb = Math.min(b, render[1]);
            if (ra < rb) {
                args.push("--render-seeds", `${ra}:${rb}`, "--size", String(size), "--engine", engine);
                renders = true;
            }
        }
        args.push("--threads", String(threads), "--texture-size", String(textureSize), "--format", format);
        if (!textures) args.push("--no-textures");

        const task = runnerTask(`seeds-${a}-${b}`, renders ? "" : python, runner, args, b - a);
        job.addTask(task);
        seedTasks.push(task);
    }

    if (merge) {
        // Fails (and so shows the job as failed) when a seed of the range has
        // no record or a file no longer matches it.
        // --preset and the glTF options give the merge the preset hash whose
        // seeds must all be there.
        const mergeArgs = ["--merge-manifest", outDir, "--seeds", `${first}:${end}`, "--verify",
            "--preset", preset, "--texture-size", String(textureSize), "--format", format];
        if (!textures) mergeArgs.push("--no-textures");
        const task = runnerTask("merge-manifest", python, runner, mergeArgs, 0);
        for (const t of seedTasks) task.addDependency(t);
        job.addTask(task);
    }
}

// A task running the runner: with Python (exec: PYTHON RUNNER -- ARGS) when
// `python` is given, else in Blender without a blend file:
// {blender} {blenderArgs} --factory-startup --python-exit-code 1 --python RUNNER -- ARGS.
function runnerTask(name, python, runner, runnerArgs, steps) {
    if (python !== "") {
        const task = author.Task(name, "misc");
        task.addCommand(author.Command("exec", {
            exe: python,
            args: [runner, "--"].concat(runnerArgs),
        }, steps));
        return task;
    }
    const task = author.Task(name, "blender");
    task.addCommand(author.Command("blender-render", {
        exe: "{blender}",
        exeArgs: "{blenderArgs}",
        argsBefore: ["--factory-startup"],
        blendfile: "",
        // Without --python-exit-code Blender exits 0 when the script raises,
        // and the task would count as done.
        args: ["--python-exit-code", "1", "--python", runner, "--"].concat(runnerArgs),
    }, steps));
    return task;
}
