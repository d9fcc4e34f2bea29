#!/usr/bin/env node
// Runs a Flamenco job type's compileJob() offline, in node, and prints the
// tasks it authors as JSON: a dry run of a job, and the harness of
// tests/batch/test_flamenco_jobtype.py.
//
// It stands in for the Manager's job compiler (goja) with the globals a job
// type sees there (author.Task/Command, print, alert, path, process) and, with
// --var, for the Manager's "{name}" variable expansion and the argv a Worker
// runs: for blender-render exe, then exeArgs split like a shell, argsBefore,
// the blendfile when not empty, args; for exec exe and args. It is written from Flamenco 3's documented
// behaviour; it contains none of Flamenco's code.
//
//   node compile_job.mjs JOBTYPE.js [--settings JSON] [--var NAME=VALUE]... [--job-type-info]
// Exit 0 with the JSON on stdout; 2 when compileJob throws (message on stderr);
// 1 on bad usage.
import fs from "node:fs";
import path from "node:path";
import vm from "node:vm";

function usage(msg) {
    process.stderr.write(`compile_job: ${msg}\nusage: compile_job.mjs JOBTYPE.js [--settings JSON] [--var NAME=VALUE]... [--job-type-info]\n`);
    process.exit(1);
}

// POSIX-shell word splitting (quotes, backslashes), as the Worker applies to exeArgs.
export function shellSplit(s) {
    const words = [];
    let cur = "", inWord = false, i = 0;
    while (i < s.length) {
        const c = s[i];
        if (c === "'") {
            const j = s.indexOf("'", i + 1);
            if (j < 0) throw new Error(`unclosed ' in ${JSON.stringify(s)}`);
            cur += s.slice(i + 1, j); inWord = true; i = j + 1;
        } else if (c === '"') {
            i++; inWord = true;
            while (i < s.length && s[i] !== '"') {
                if (s[i] === "\\" && i + 1 < s.length && '"\\$`'.includes(s[i + 1])) i++;
                cur += s[i++];
            }
            if (i >= s.length) throw new Error(`unclosed " in ${JSON.stringify(s)}`);
            i++;
        } else if (c === "\\" && i + 1 < s.length) {
            cur += s[i + 1]; inWord = true; i += 2;
        } else if (/\s/.test(c)) {
            if (inWord) { words.push(cur); cur = ""; inWord = false; }
            i++;
        } else {
            cur += c; inWord = true; i++;
        }
    }
    if (inWord) words.push(cur);
    return words;
}

// The Manager expands "{name}" in a command's string parameters and in the
// string items of its list parameters, and nothing deeper.
function expandOne(s, vars) {
    for (const [k, v] of Object.entries(vars)) s = s.split(`{${k}}`).join(v);
    return s;
}

function expandParams(params, vars) {
    const out = {};
    for (const [key, value] of Object.entries(params)) {
        if (typeof value === "string") out[key] = expandOne(value, vars);
        else if (Array.isArray(value)) out[key] = value.map((v) => (typeof v === "string" ? expandOne(v, vars) : v));
        else out[key] = value;
    }
    return out;
}

function workerArgv(params) {
    if (typeof params.exe !== "string" || params.exe === "") throw new Error("blender-render: missing 'exe'");
    const argv = [params.exe, ...shellSplit(params.exeArgs || ""), ...(params.argsBefore || []).map(String)];
    if (params.blendfile) argv.push(String(params.blendfile));
    argv.push(...(params.args || []).map(String));
    return argv;
}

export function compile(jobTypeFile, settings, vars) {
    const src = fs.readFileSync(jobTypeFile, "utf8");
    const log = [];
    const author = {
        Task(name, type) {
            name = String(name ?? "").trim(); type = String(type ?? "").trim();
            if (!name) throw new Error("author.Task(name, type): name is required");
            if (!type) throw new Error("author.Task(name, type): type is required");
            const t = {
                name, type, priority: 50, commands: [], dependencies: [],
                addCommand(c) { t.commands.push(c); },
                addDependency(d) { t.dependencies.push(d); },
            };
            return t;
        },
        Command(name, parameters, totalStepCount) {
            return { name, parameters, totalStepCount: totalStepCount || 0 };
        },
    };
    const ctx = vm.createContext({
        author,
        print: (...a) => log.push(a.map(String).join(" ")),
        alert: (...a) => log.push("ALERT " + a.map(String).join(" ")),
        path: {
            join: (...p) => path.posix.join(...p), dirname: path.posix.dirname,
            basename: (p) => path.posix.basename(p), stem: (p) => path.posix.parse(p).name,
        },
        process: { platform: "linux" },
    });
    vm.runInContext(src, ctx, { filename: jobTypeFile });
    // Top-level const/function bindings live in the context's lexical scope.
    const { JOB_TYPE, compileJob } = vm.runInContext(
        "({JOB_TYPE: typeof JOB_TYPE === 'undefined' ? undefined : JOB_TYPE," +
        " compileJob: typeof compileJob === 'undefined' ? undefined : compileJob})", ctx);
    if (!JOB_TYPE || !Array.isArray(JOB_TYPE.settings)) throw new Error("script does not define JOB_TYPE with settings");
    if (typeof compileJob !== "function") throw new Error("script does not define compileJob(job)");

    const tasks = [];
    const job = {
        name: "banyan-test", type: path.basename(jobTypeFile, ".js").replaceAll("_", "-"),
        priority: 50, created: new Date(0), settings: { ...settings }, metadata: {},
        addTask(t) { tasks.push(t); },
    };
    compileJob(job);
    return {
        jobType: JOB_TYPE,
        log,
        tasks: tasks.map((t) => ({
            name: t.name, type: t.type,
            dependencies: t.dependencies.map((d) => d.name),
            commands: t.commands.map((c) => {
                const params = vars ? expandParams(c.parameters, vars) : c.parameters;
                const out = { name: c.name, parameters: params, totalStepCount: c.totalStepCount };
                if (vars && c.name === "blender-render") out.argv = workerArgv(params);
                if (vars && c.name === "exec") out.argv = [params.exe, ...(params.args || []).map(String)];
                return out;
            }),
        })),
    };
}

function main(argv) {
    let file = null, settings = {}, vars = null, info = false;
    for (let i = 0; i < argv.length; i++) {
        const a = argv[i];
        if (a === "--settings") settings = JSON.parse(argv[++i] ?? usage("--settings needs JSON"));
        else if (a === "--var") {
            const kv = argv[++i] ?? usage("--var needs NAME=VALUE");
            const eq = kv.indexOf("=");
            if (eq <= 0) usage(`--var ${kv}: expected NAME=VALUE`);
            vars = vars || {};
            vars[kv.slice(0, eq)] = kv.slice(eq + 1);
        } else if (a === "--job-type-info") info = true;
        else if (!file && !a.startsWith("--")) file = a;
        else usage(`unknown argument ${a}`);
    }
    if (!file) usage("no job type file");
    let result;
    try {
        result = compile(file, settings, vars);
    } catch (e) {
        process.stderr.write(`compileJob failed: ${e && e.message !== undefined ? e.message : String(e)}\n`);
        process.exit(2);
    }
    process.stdout.write(JSON.stringify(info ? result.jobType : result, null, 1) + "\n");
}

if (import.meta.url === `file://${process.argv[1]}` || process.argv[1]?.endsWith("compile_job.mjs")) {
    main(process.argv.slice(2));
}
