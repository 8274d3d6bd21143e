#!/usr/bin/env python3
"""Checks what simlab writes for a grading platform against the fields that platform documents.

  validate_platforms.py prairielearn RESULTS [--score F] [--points N] [--max N] [--gradable yes|no]
      PrairieLearn's external grader results.json (docs/externalGrading.md): score in [0, 1], gradable,
      format_errors, message, output, images, tests[] with name, description, points, max_points, message,
      output, images ({label, url} with a data URI); at most 1 MB.
  validate_platforms.py prairielearn-info INFO
      A question's info.json (PrairieLearn's strict schema for question info, schemas/infoQuestion.ts), external
      grading enabled.
  validate_platforms.py classroom EARNED MISSED [--points N] [--max N] [--status S]
      GitHub Classroom's two runner results, as autograding-grading-reporter@v1 reads them (JSON, or its base64),
      and the reporter's two totals computed as it computes them: its console table's (tests passed / tests x
      max_score for each runner) and the points it records (the tests' scores over the runners' max_score). Both
      must be N of the N given by --max; --status is the status of the missed runner (the earned one passes).
  validate_platforms.py workflow YML STEP
      The Classroom workflow: the names Classroom looks for, a step STEP that writes `earned` and `missed` to
      GITHUB_OUTPUT, and the reporter reading EARNED_RESULTS and MISSED_RESULTS from it.

Exit 0 when valid and as expected; 1 with one line per problem otherwise.
"""
import base64
import json
import math
import re
import sys

problems = []


def expect(ok, what):
    if not ok:
        problems.append(what)


def number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def options(args):
    out = {}
    for i in range(0, len(args) - 1, 2):
        out[args[i].lstrip("-")] = args[i + 1]
    return out


def check_images(images, where):
    expect(isinstance(images, list), where + ".images is not a list")
    for k, image in enumerate(images if isinstance(images, list) else []):
        at = "%s.images[%d]" % (where, k)
        expect(isinstance(image, dict) and set(image) <= {"label", "url"}, at + " has unknown keys")
        if not isinstance(image, dict):
            continue
        expect(isinstance(image.get("label", ""), str), at + ".label is not a string")
        url = image.get("url")
        ok = isinstance(url, str) and re.match(r"^data:image/[a-z0-9.+-]+;base64,[A-Za-z0-9+/]*={0,2}$", url)
        expect(ok, at + ".url is not a base64 data URI of an image")
        if ok:
            base64.b64decode(url.split(",", 1)[1], validate=True)


def prairielearn(path, opts):
    raw = open(path, "rb").read()
    expect(len(raw) <= 1000000, "the file has %d bytes; PrairieLearn takes 1 MB" % len(raw))
    doc = json.loads(raw.decode("utf-8"))
    expect(isinstance(doc, dict), "the document is not an object")
    known = {"gradable", "score", "format_errors", "message", "output", "images", "tests"}
    for key in doc:
        expect(key in known, "unknown top-level key " + key)
    gradable = doc.get("gradable", True)
    expect(isinstance(gradable, bool), "gradable is not a boolean")
    if gradable:
        expect(number(doc.get("score")) and 0 <= doc["score"] <= 1, "score is missing or not in [0, 1]")
    else:
        fe = doc.get("format_errors")
        expect(isinstance(fe, str) or (isinstance(fe, list) and fe and all(isinstance(x, str) for x in fe)),
               "not gradable, and format_errors is not a string or a list of strings")
    for key in ("message", "output"):
        expect(isinstance(doc.get(key, ""), str), key + " is not a string")
    if "images" in doc:
        check_images(doc["images"], "")
    tests = doc.get("tests", [])
    expect(isinstance(tests, list), "tests is not a list")
    points = max_points = 0
    for i, t in enumerate(tests if isinstance(tests, list) else []):
        at = "tests[%d]" % i
        expect(isinstance(t, dict), at + " is not an object")
        if not isinstance(t, dict):
            continue
        for key in t:
            expect(key in {"name", "description", "points", "max_points", "message", "output", "images"},
                   at + " has the unknown key " + key)
        expect(isinstance(t.get("name"), str) and t["name"], at + ".name is missing")
        for key in ("description", "message", "output"):
            expect(isinstance(t.get(key, ""), str), at + "." + key + " is not a string")
        expect(number(t.get("points")) and number(t.get("max_points")) and 0 <= t["points"] <= t["max_points"],
               at + ": points and max_points are not numbers with 0 <= points <= max_points")
        if number(t.get("points")) and number(t.get("max_points")):
            points += t["points"]
            max_points += t["max_points"]
        if "images" in t:
            check_images(t["images"], at)
    if gradable and max_points > 0:
        expect(abs(doc.get("score", -1) - points / max_points) < 1e-9, "score is not the tests' points over their maximum")
    if "score" in opts:
        expect(abs(doc.get("score", -1) - float(opts["score"])) < 1e-9, "score is %s, not %s" % (doc.get("score"), opts["score"]))
    if "points" in opts:
        expect(abs(points - float(opts["points"])) < 0.005, "the tests' points add up to %g, not %s" % (points, opts["points"]))
    if "max" in opts:
        expect(abs(max_points - float(opts["max"])) < 0.005, "the tests' max_points add up to %g, not %s" % (max_points, opts["max"]))
    if "gradable" in opts:
        expect(gradable == (opts["gradable"] == "yes"), "gradable is %s" % gradable)


def prairielearn_info(path):
    info = json.load(open(path))
    known = {"comment", "uuid", "type", "title", "topic", "tags", "authors", "clientFiles", "clientTemplates",
             "template", "gradingMethod", "singleVariant", "showCorrectAnswer", "partialCredit", "options",
             "externalGradingOptions", "dependencies", "workspaceOptions", "sharingSets", "sharePublicly",
             "shareSourcePublicly", "preferences"}
    for key in info:
        expect(key in known, "info.json: unknown key " + key)
    expect(isinstance(info.get("uuid"), str) and
           re.match(r"^[0-9a-fA-F]{8}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{12}$", info["uuid"]),
           "info.json: uuid is not a UUID")
    expect(info.get("type") == "v3", "info.json: type is not v3")
    expect(isinstance(info.get("title"), str) and info["title"], "info.json: no title")
    expect(isinstance(info.get("topic"), str) and info["topic"], "info.json: no topic")
    expect(all(isinstance(t, str) for t in info.get("tags", [])), "info.json: tags are not strings")
    expect(info.get("gradingMethod") == "External", "info.json: gradingMethod is not External")
    ego = info.get("externalGradingOptions", {})
    for key in ego:
        expect(key in {"comment", "enabled", "image", "entrypoint", "serverFilesCourse", "timeout",
                       "enableNetworking", "environment"}, "info.json: unknown externalGradingOptions key " + key)
    expect(ego.get("enabled") is True, "info.json: external grading is not enabled")
    expect(isinstance(ego.get("image"), str) and ego["image"], "info.json: no image")
    entry = ego.get("entrypoint")
    expect(isinstance(entry, str) and entry.startswith("/") or
           isinstance(entry, list) and entry and all(isinstance(x, str) for x in entry), "info.json: entrypoint")
    timeout = ego.get("timeout", 30)
    expect(isinstance(timeout, int) and not isinstance(timeout, bool) and 0 < timeout <= 600,
           "info.json: timeout is not a whole number of seconds up to 600")
    expect(ego.get("enableNetworking", False) is False, "info.json: the grader has the network")


def runner_result(path):
    text = open(path).read().strip()
    if not text.startswith("{"):
        text = base64.b64decode(text, validate=True).decode("utf-8")
    doc = json.loads(text)
    for key in doc:
        expect(key in {"version", "status", "max_score", "tests"}, "unknown key " + key)
    expect(doc.get("version") == 1, "version is not 1")
    expect(doc.get("status") in ("pass", "fail", "error"), "status is not pass, fail or error")
    expect(number(doc.get("max_score")) and doc["max_score"] >= 0, "max_score is not a number")
    tests = doc.get("tests")
    # The reporter divides by the number of tests.
    expect(isinstance(tests, list) and tests, "tests is not a list of tests")
    score = 0
    for i, t in enumerate(tests if isinstance(tests, list) else []):
        at = "tests[%d]" % i
        for key in t:
            expect(key in {"name", "status", "score", "message", "test_code", "filename", "line_no", "duration"},
                   at + " has the unknown key " + key)
        expect(isinstance(t.get("name"), str) and t["name"], at + ".name is missing")
        expect(t.get("status") in ("pass", "fail", "error"), at + ".status is not pass, fail or error")
        expect(number(t.get("score")) and t["score"] >= 0, at + ".score is not a number")
        expect(t.get("message") is None or isinstance(t["message"], str), at + ".message is not a string")
        for key in ("test_code", "filename"):
            expect(isinstance(t.get(key, ""), str), at + "." + key + " is not a string")
        # The reporter prints " - line N" after the name unless line_no is 0.
        expect(t.get("line_no") == 0, at + ".line_no is not 0")
        expect(number(t.get("duration", 0)), at + ".duration is not a number")
        score += t.get("score", 0) if number(t.get("score")) else 0
    if number(doc.get("max_score")):
        expect(score <= doc["max_score"] + 0.005, "the tests' scores add up to more than max_score")
    return doc


def classroom(paths, opts):
    runners = [runner_result(p) for p in paths]
    if problems:
        return
    # The console table (aggregate-results.js, test-helpers.js getTestScore): per runner, tests passed / tests x
    # max_score; its Total row adds them up.
    table = sum(sum(t["status"] == "pass" for t in r["tests"]) / len(r["tests"]) * (r["max_score"] or 0)
                for r in runners)
    table_max = sum(r["max_score"] for r in runners)
    # The points recorded for Classroom (notify-classroom.js): runners with a max_score, their tests' scores.
    recorded = sum(t["score"] for r in runners if r["max_score"] for t in r["tests"])
    recorded_max = sum(r["max_score"] for r in runners if r["max_score"])
    expect(abs(table - recorded) < 0.005 and abs(table_max - recorded_max) < 0.005,
           "the reporter's table gives %g/%g but it records %g/%g" % (table, table_max, recorded, recorded_max))
    if "points" in opts:
        expect(abs(recorded - float(opts["points"])) < 0.005, "the points recorded are %g, not %s" % (recorded, opts["points"]))
    if "max" in opts:
        expect(abs(recorded_max - float(opts["max"])) < 0.005, "the maximum recorded is %g, not %s" % (recorded_max, opts["max"]))
    if "status" in opts:
        expect(runners[-1].get("status") == opts["status"], "status is %s, not %s" % (runners[-1].get("status"), opts["status"]))


def workflow(path, runner):
    import yaml
    doc = yaml.safe_load(open(path))
    expect(doc.get("name") == "Autograding Tests", "the workflow is not named 'Autograding Tests'")
    on = doc.get("on", doc.get(True))  # YAML 1.1 reads a bare `on` as true
    events = on if isinstance(on, list) else list(on or {})
    expect("push" in events, "the workflow does not run on push")
    jobs = doc.get("jobs", {})
    expect(list(jobs) == ["run-autograding-tests"], "the workflow's one job is not run-autograding-tests")
    job = jobs.get("run-autograding-tests", {})
    expect(isinstance(job.get("runs-on"), str), "the job has no runs-on")
    steps = job.get("steps", [])
    expect(any(str(s.get("uses", "")).startswith("actions/checkout@") for s in steps), "no checkout step")
    ids = [s.get("id") for s in steps]
    expect(runner in ids, "no step with the id " + runner)
    if runner in ids:
        step = steps[ids.index(runner)]
        run = step.get("run", "")
        expect("--format classroom" in run, "the step %s does not run simlab check --format classroom" % runner)
        for output in ("earned", "missed"):
            expect(re.search(r'echo "%s=\$\([^)]*base64 -w 0\)" >>"\$GITHUB_OUTPUT"' % output, run),
                   "the step %s does not write %s, in base64, to GITHUB_OUTPUT" % (runner, output))
        expect(step.get("if") == "always()", "the step %s does not run when the build failed" % runner)
    reporters = [s for s in steps if str(s.get("uses", "")) == "classroom-resources/autograding-grading-reporter@v1"]
    expect(len(reporters) == 1, "no step uses classroom-resources/autograding-grading-reporter@v1")
    if reporters:
        reporter = reporters[0]
        runners = str(reporter.get("with", {}).get("runners", ""))
        expect(runners == "earned,missed", "the reporter's runners are not earned,missed")
        env = reporter.get("env", {})
        for output in ("earned", "missed"):
            wanted = "${{ steps.%s.outputs.%s }}" % (runner, output)
            expect(env.get(output.upper() + "_RESULTS") == wanted, "the reporter does not read %s_RESULTS from %s" %
                   (output.upper(), wanted))
        expect(reporter.get("if") == "always()", "the reporter does not run when a step failed")
        expect(ids.index(runner) < steps.index(reporter), "the reporter runs before the tests")


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    kind, path, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    try:
        if kind == "prairielearn":
            prairielearn(path, options(rest))
        elif kind == "prairielearn-info":
            prairielearn_info(path)
        elif kind == "classroom":
            classroom([path, rest[0]], options(rest[1:]))
        elif kind == "workflow":
            workflow(path, rest[0])
        else:
            print("unknown kind " + kind)
            return 2
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        problems.append("%s: %s" % (type(e).__name__, e))
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
