"""The documentation says what the code does: the option defaults of the README and of docs/cli.md (the
full CLI reference) against the tool's --help, docs/cli.md's JSON keys against real reports,
python/README.md's defaults and names against the module, its API snippet runs as pasted, docs/http-api.md
against the server's routes and answers, the version is the same everywhere, and every relative link in
the README and docs/ points to a file (and heading) that exists."""
import ast
import json
import os
import re
import signal
import subprocess
import sys
import urllib.request

import pytest

import iarap
from conftest import REPO

README = (REPO / "README.md").read_text()
CLI_DOC = (REPO / "docs" / "cli.md").read_text()
OPTIONS_DOC = (REPO / "docs" / "options.md").read_text()
PYTHON_README = (REPO / "python" / "README.md").read_text()
HTTP_API = (REPO / "docs" / "http-api.md").read_text()
VERSION = (REPO / "VERSION").read_text().strip()


def section(text, heading):
    """The text under a Markdown heading that starts with `heading`, up to the next heading of any level
    (lines starting with # inside ``` blocks are code, not headings)."""
    lines, inside, fenced = [], False, False
    for line in text.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        is_heading = not fenced and re.match(r"#+ ", line)
        if is_heading and inside:
            break
        if inside:
            lines.append(line)
        inside = inside or bool(is_heading and line.lstrip("#").strip().startswith(heading))
    assert lines, f"no section {heading!r}"
    return "\n".join(lines) + "\n"


def backticked(text):
    return re.findall(r"`([a-z_]+)`", text)


def sentence(text, start):
    """From `start` (line breaks in the text may fall anywhere) to the next period that ends a sentence."""
    found = re.search(r"\s+".join(map(re.escape, start.split())), text)
    assert found, f"the documentation no longer says {start!r}"
    end = re.compile(r"\.(\s|$)").search(text, found.end())
    return text[found.start():end.start() + 1]


def test_version_is_the_same_everywhere():
    assert iarap.__version__ == VERSION
    assert f"Version {VERSION} " in README
    assert f"## [{VERSION}]" in (REPO / "CHANGELOG.md").read_text()
    assert re.search(rf"^version: {re.escape(VERSION)}$", (REPO / "CITATION.cff").read_text(), re.M)


def test_version_flag(cli):
    run = subprocess.run([cli, "--version"], capture_output=True, text=True)
    assert run.returncode == 0 and run.stdout.strip() == f"iarap {VERSION}"


NUMBER_WORDS = {8: "eight", 9: "nine", 10: "ten", 11: "eleven", 12: "twelve", 13: "thirteen", 14: "fourteen"}


def registered_commands(cli):
    """The subcommands the tool registers, from the list `iarap --help` prints (CLI11: "Subcommands:")."""
    help_text = subprocess.run([cli, "--help"], capture_output=True, text=True, check=True).stdout
    listed = help_text.split("Subcommands:", 1)[1]
    return sorted(re.findall(r"^  ([a-z]+)\b", listed, re.M))


def test_documented_commands_are_the_registered_ones(cli):
    """The README and docs/cli.md count the subcommands in words and name each; docs/cli.md has a table row
    and a section per subcommand, the README a task section; all as the tool's own list."""
    commands = registered_commands(cli)
    assert len(commands) >= 9 and "param" in commands and "batch" in commands, commands
    count = NUMBER_WORDS[len(commands)]
    tool = section(README, "The `iarap` tool, by task")
    assert re.match(rf"{count.capitalize()} subcommands \(([^)]*)\)", tool.strip()), \
        f"the README should open its tool section with '{count.capitalize()} subcommands (...)'"
    assert sorted(re.findall(r"`([a-z]+)`", re.match(r"[^(]*\(([^)]*)\)", tool.strip()).group(1))) == commands
    assert f"the {count} subcommands" in CLI_DOC.lower().replace("\n", " ")
    for wrong in set(NUMBER_WORDS.values()) - {count}:
        for text, where in ((README, "README"), (CLI_DOC, "docs/cli.md")):
            assert not re.search(rf"\b{wrong} subcommands", text, re.I), f"{where} says {wrong} subcommands"
    table = set(re.findall(r"^\| \[`iarap ([a-z]+)", CLI_DOC, re.M))
    headings = set(re.findall(r"^## `iarap ([a-z]+)`", CLI_DOC, re.M))
    tasks = set(re.findall(r"`iarap ([a-z]+)`", "\n".join(re.findall(r"^### .*", README, re.M))))
    for name, documented in (("docs/cli.md's table", table), ("docs/cli.md's sections", headings),
                             ("the README's task headings", tasks)):
        assert documented == set(commands), f"{name}: missing {sorted(set(commands) - documented)}, " \
                                            f"not a command {sorted(documented - set(commands))}"


def test_readme_length():
    """The README stays a front page (issue 43: at most 350 lines); detail goes to docs/."""
    assert len(README.splitlines()) <= 350


def documented_defaults(table):
    """{option: default} from the rows of a Markdown option table that give a default."""
    return dict(re.findall(r"^\| `(--[a-z-]+)[^`]*` \| `?([^|`]+?)`? \|", table, re.M))


def test_deform_option_defaults(cli):
    """Every row with a default of docs/cli.md's full deform table and of the README's short one matches the
    default --help prints; the README's rows are rows of the full table."""
    full = documented_defaults(section(CLI_DOC, "`iarap deform"))
    short = documented_defaults(section(README, "Deform a mesh"))
    required = {"--method", "--boundary", "--iterations", "--tolerance", "--threads"}
    assert required <= set(full)
    assert required <= set(short)
    assert set(short) <= set(full), f"README's deform table has {sorted(set(short) - set(full))}, docs/cli.md not"
    help_text = subprocess.run([cli, "deform", "--help"], capture_output=True, text=True, check=True).stdout
    # CLI11 prints "  --iterations INT:INT in [0 - 1000000]=50": the default follows the last "=".
    shown = dict(re.findall(r"^\s+(--[a-z-]+) .*=(\S+)$", help_text, re.M))
    for where, documented in (("docs/cli.md", full), ("README", short)):
        for option, default in documented.items():
            assert option in shown, f"{option} shows no default in --help:\n{help_text}"
            assert float(default) == float(shown[option]) if re.match(r"[\d.e+-]+$", default) else \
                default == shown[option], f"{option}: {where} {default}, --help {shown[option]}"


def test_deform_report_keys(cli, tmp_path):
    report = json.loads(subprocess.run(
        [cli, "deform", REPO / "data" / "bunny.off", "--scenario", REPO / "data" / "bunny_scenario.json",
         "--iterations", "2", "--out", tmp_path / "out.off", "--json", "--quiet"],
        capture_output=True, text=True, check=True).stdout)
    text = section(CLI_DOC, "`iarap deform")
    # repair: only with --repair; bench: a pointer to the bench command. The solve's own fields (the same in
    # every front-end's report) are listed once, in docs/options.md.
    top = set(backticked(sentence(text, "The\nreport holds"))) - {"repair", "bench"}
    solve = set(backticked(sentence(section(OPTIONS_DOC, "The report"), "Its fields are")))
    assert solve <= set(report), f"docs/options.md lists {sorted(solve - set(report))} not in the report"
    top |= solve
    assert top == set(report), f"docs/cli.md lists {sorted(top - set(report))} not in the report, " \
                               f"misses {sorted(set(report) - top)}"
    nested = set(backticked(sentence(text, "For iARAP, `intrinsic` holds"))) - {"intrinsic"}
    assert nested == set(report["intrinsic"])


def test_info_json_keys(cli):
    report = json.loads(subprocess.run([cli, "info", "--json", REPO / "data" / "bunny.off"],
                                       capture_output=True, text=True, check=True).stdout)
    text = section(CLI_DOC, "`iarap info")
    nested = set(backticked(sentence(text, "reports, in the JSON under the key `intrinsic`"))) - {"intrinsic"}
    assert nested == set(report["intrinsic"])
    assert not nested & set(report)  # docs/cli.md says they are nested, and they are


def python_signature(function):
    """{name: default} from the signature pybind11 writes on a docstring's first line."""
    tree = ast.parse("def " + function.__doc__.splitlines()[0] + ": pass").body[0].args
    names = [a.arg for a in tree.args + tree.kwonlyargs]
    defaults = [None] * (len(tree.args) - len(tree.defaults)) + list(tree.defaults) + list(tree.kw_defaults)
    return {n: ast.literal_eval(d) for n, d in zip(names, defaults) if d is not None}


def test_python_readme_defaults_and_names():
    api = section(PYTHON_README, "API")
    init = python_signature(iarap.ARAP.__init__)
    for name, value in re.findall(r"(\w+)=(True|False)\b", api):
        if name in init:
            assert init[name] == (value == "True"), f"{name}: README {value}, module {init[name]}"
    solve = python_signature(iarap.ARAP.solve)
    call = re.search(r"solver\.solve\((.*)\)", api).group(1)
    for name, value in re.findall(r"(\w+)=([^,)]+)", call):
        assert solve[name] == ast.literal_eval(value), name
    for names in (iarap.LAPLACIAN_KINDS, iarap.MASS_KINDS, iarap.ARAP_METHODS):
        for name in names:
            assert f'"{name}"' in api, f"{name} is not in python/README.md's API"


def test_python_readme_snippet_runs(tmp_path):
    """The API block runs as pasted (from a folder that has the repository's data/)."""
    code = re.search(r"## API\n\n```python\n(.*?)```", PYTHON_README, re.S).group(1)
    (tmp_path / "data").symlink_to(REPO / "data")
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(iarap.__file__)))
    run = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, env=env,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "out.obj").exists()


def test_http_api_routes_are_the_servers():
    # One route file per resource (app/serve/*_route(s).cpp).
    source = "".join(path.read_text() for path in sorted((REPO / "app" / "serve").glob("*.cpp")))
    implemented = set(re.findall(r'routes\.(get|post)\("(/api/[a-z_/]+)"', source))
    documented = {(m.lower(), p) for m, p in re.findall(r"^\| `(GET|POST) (/api/[a-z_/]+)", HTTP_API, re.M)}
    assert len(implemented) >= 14
    assert documented == implemented


def test_http_api_session_json(cli):
    """The documented session JSON has the keys (and nesting) of a real /api/state answer."""
    example = json.loads(re.search(r"\*\*Session JSON\*\*.*?```json\n(.*?)```", HTTP_API, re.S).group(1))
    server = subprocess.Popen([cli, "serve", "--port", "0", REPO / "data" / "bunny.off"], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    try:
        port = re.search(r"127\.0\.0\.1:(\d+)/", server.stdout.readline()).group(1)
        base = f"http://127.0.0.1:{port}/api/"
        request = urllib.request.Request(base + "constraints", method="POST",
                                         data=json.dumps({"fixed": [12, 40], "handle": [7]}).encode(),
                                         headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(request, timeout=60) as response:
            state = json.load(response)
    finally:
        server.send_signal(signal.SIGTERM)
        server.wait(timeout=60)

    def keys(value):
        if isinstance(value, dict):
            return {k: keys(v) for k, v in value.items()}
        return type(value).__name__ if value is not None else None

    assert keys(example) == keys(state)
    assert state["mesh"]["vertices"] == 3485 and state["fixed"] == [12, 40] and state["handle"] == [7]


def heading_anchors(text):
    """The anchors GitHub gives a Markdown file's headings: lower case, punctuation dropped, spaces to
    hyphens, "-1", "-2" ... on repeats (lines inside ``` blocks are code, not headings)."""
    anchors, fenced = set(), False
    for line in text.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        heading = not fenced and re.match(r"#+ (.*)", line)
        if heading:
            anchor = re.sub(r"[^\w\- ]", "", heading.group(1).strip().lower()).replace(" ", "-")
            repeat, unique = 0, anchor
            while unique in anchors:
                repeat += 1
                unique = f"{anchor}-{repeat}"
            anchors.add(unique)
    return anchors


def test_relative_links_resolve():
    """Every relative link of the README and of docs/*.md (and docs/*/*.md) names a file that exists, and
    a #fragment into a Markdown file names one of its headings."""
    documents = [REPO / "README.md"] + sorted((REPO / "docs").glob("*.md")) + sorted((REPO / "docs").glob("*/*.md"))
    assert len(documents) >= 8
    broken = []
    for document in documents:
        text = re.sub(r"^```.*?^```", "", document.read_text(), flags=re.S | re.M)  # no links in code blocks
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue  # https:, mailto:
            path, _, fragment = target.partition("#")
            file = (document.parent / path).resolve() if path else document
            if not file.exists():
                broken.append(f"{document.relative_to(REPO)}: {target} (no such file)")
            elif fragment and file.suffix == ".md" and fragment not in heading_anchors(file.read_text()):
                broken.append(f"{document.relative_to(REPO)}: {target} (no such heading)")
    assert not broken, "\n".join(broken)
