//! The cluster examples of `examples/cluster/`, checked without a cluster:
//!
//! - the Kubernetes manifest against what an Indexed Job requires (read with a small YAML
//!   reader of the subset the manifest uses, which refuses anything else), and its shard count
//!   `completions` against the shard command's N and `parallelism`;
//! - the SLURM script against a stand-in `sbatch` that answers as a one-node cluster of 2 CPUs
//!   does: a request for more CPUs per task is refused at once in one line and nothing is
//!   submitted, and the job array is `--array=0-(N-1)` for N shards.
//!
//! `scripts/check-slurm.sh` runs the SLURM script on a real one-node SLURM.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

mod support;
use support::Scratch;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

// ---------------------------------------------------------------------------------------------
// A YAML reader for the block style of Kubernetes manifests: mappings, sequences (`- `), plain
// and quoted scalars, flow sequences of scalars (`["bash", "-c"]`), folded and literal block
// scalars (`>-`, `|`), comments and `---` between documents. Anchors, tags, flow mappings and
// multi-line plain scalars are refused with the line, so that the checks never read a file
// other than the way Kubernetes would.

#[derive(Debug, Clone, PartialEq)]
enum Yaml {
    /// A scalar's text, and whether it was quoted (a quoted `"8"` is a string, a plain `8` a
    /// number).
    Scalar(String, bool),
    Seq(Vec<Yaml>),
    Map(Vec<(String, Yaml)>),
}

/// One line with content: its number (from 1), indent and text without the comment.
#[derive(Debug, Clone)]
struct Line {
    no: usize,
    indent: usize,
    text: String,
}

/// `text` without a trailing comment (a `#` at the start or after a space, outside quotes).
fn strip_comment(text: &str) -> &str {
    let (mut single, mut double) = (false, false);
    let mut prev = ' ';
    for (i, c) in text.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && prev == ' ' => return text[..i].trim_end(),
            _ => {}
        }
        prev = c;
    }
    text.trim_end()
}

/// The documents of `src`.
fn parse_yaml(src: &str) -> Vec<Yaml> {
    let mut docs = Vec::new();
    let mut lines: Vec<Line> = Vec::new();
    // The indent of the key whose block scalar (`>-`, `|`) is being read: its lines are text,
    // a `#` in them included.
    let mut block_scalar_of: Option<usize> = None;
    let end = src.lines().count() + 1;
    for (no, l) in src
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .chain([(end, "---")])
    {
        assert!(!l.contains('\t'), "line {no}: a tab");
        let indent = l.len() - l.trim_start().len();
        if block_scalar_of.is_some_and(|key| indent > key || l.trim().is_empty()) {
            if !l.trim().is_empty() {
                lines.push(Line {
                    no,
                    indent,
                    text: l.trim().to_owned(),
                });
            }
            continue;
        }
        block_scalar_of = None;
        if l.trim_end() == "---" {
            if !lines.is_empty() {
                let mut i = 0;
                let indent = lines[0].indent;
                let doc = block(&mut lines, &mut i, indent);
                assert!(
                    i == lines.len(),
                    "line {}: not part of the document",
                    lines[i].no
                );
                docs.push(doc);
                lines.clear();
            }
            continue;
        }
        let text = strip_comment(l.trim_start());
        if text.is_empty() {
            continue;
        }
        let opens_block_scalar = BLOCK_SCALARS.iter().any(|b| {
            text == format!("- {b}")
                || text.ends_with(&format!(": {b}"))
                || text.ends_with(&format!(" - {b}"))
        });
        if opens_block_scalar {
            block_scalar_of = Some(indent);
        }
        lines.push(Line {
            no,
            indent,
            text: text.to_owned(),
        });
    }
    docs
}

/// The node whose lines start at `lines[*i]`, all at `indent`.
fn block(lines: &mut [Line], i: &mut usize, indent: usize) -> Yaml {
    let first = lines[*i].clone();
    assert!(
        first.indent == indent,
        "line {}: indented {} where {indent} was expected",
        first.no,
        first.indent
    );
    if first.text == "-" || first.text.starts_with("- ") {
        let mut items = Vec::new();
        while *i < lines.len()
            && lines[*i].indent == indent
            && (lines[*i].text == "-" || lines[*i].text.starts_with("- "))
        {
            let l = lines[*i].clone();
            if l.text == "-" {
                *i += 1;
                assert!(
                    *i < lines.len() && lines[*i].indent > indent,
                    "line {}: an empty item",
                    l.no
                );
                let child = lines[*i].indent;
                items.push(block(lines, i, child));
            } else {
                // `- key: value` or `- scalar`: the rest is a node indented past the dash.
                let rest = l.text[2..].trim_start();
                let child = indent + (l.text.len() - rest.len());
                lines[*i] = Line {
                    no: l.no,
                    indent: child,
                    text: rest.to_owned(),
                };
                if BLOCK_SCALARS.contains(&rest) {
                    *i += 1;
                    items.push(block_scalar(lines, i, indent, rest, l.no));
                } else if is_mapping_line(rest) {
                    items.push(block(lines, i, child));
                } else {
                    *i += 1;
                    items.push(scalar(rest, l.no));
                }
            }
        }
        return Yaml::Seq(items);
    }
    let mut entries: Vec<(String, Yaml)> = Vec::new();
    while *i < lines.len() && lines[*i].indent == indent {
        let l = lines[*i].clone();
        assert!(
            is_mapping_line(&l.text),
            "line {}: expected `key: value`, found `{}`",
            l.no,
            l.text
        );
        let (key, value) = l.text.split_once(':').unwrap();
        let (key, value) = (key.trim(), value.trim());
        assert!(
            !entries.iter().any(|(k, _)| k == key),
            "line {}: `{key}` twice",
            l.no
        );
        *i += 1;
        let node = match value {
            "" => {
                assert!(*i < lines.len(), "line {}: `{key}` has no value", l.no);
                let next = lines[*i].clone();
                let seq_here = next.indent == indent && next.text.starts_with("- ");
                assert!(
                    next.indent > indent || seq_here,
                    "line {}: `{key}` has no value",
                    l.no
                );
                block(lines, i, next.indent)
            }
            v if BLOCK_SCALARS.contains(&v) => block_scalar(lines, i, indent, v, l.no),
            v => scalar(v, l.no),
        };
        entries.push((key.to_owned(), node));
    }
    assert!(
        *i == lines.len() || lines[*i].indent < indent,
        "line {}: indented {} inside a mapping at {indent}",
        lines[*i].no,
        lines[*i].indent
    );
    Yaml::Map(entries)
}

/// The block scalars read: folded (`>`) and literal (`|`), their last line break kept or not.
const BLOCK_SCALARS: [&str; 4] = [">", ">-", "|", "|-"];

/// The block scalar of style `style` whose lines follow, indented past `indent`: folded lines
/// joined by spaces, literal ones by line breaks (the last line break left out).
fn block_scalar(lines: &[Line], i: &mut usize, indent: usize, style: &str, no: usize) -> Yaml {
    let mut parts = Vec::new();
    while *i < lines.len() && lines[*i].indent > indent {
        parts.push(lines[*i].text.clone());
        *i += 1;
    }
    assert!(!parts.is_empty(), "line {no}: an empty block scalar");
    let sep = if style.starts_with('>') { " " } else { "\n" };
    Yaml::Scalar(parts.join(sep), true)
}

/// Whether `text` is `key: ...` or `key:` with a plain key.
fn is_mapping_line(text: &str) -> bool {
    text.split_once(':').is_some_and(|(k, v)| {
        !k.is_empty()
            && k.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_./".contains(c))
            && (v.is_empty() || v.starts_with(' '))
    })
}

/// A scalar or a flow sequence of scalars.
fn scalar(text: &str, no: usize) -> Yaml {
    if let Some(inner) = text.strip_prefix('[') {
        let inner = inner
            .strip_suffix(']')
            .unwrap_or_else(|| panic!("line {no}: a flow sequence must end on its line"));
        return Yaml::Seq(
            split_flow(inner, no)
                .iter()
                .map(|item| scalar(item, no))
                .collect(),
        );
    }
    for q in ['"', '\''] {
        if let Some(inner) = text.strip_prefix(q) {
            let inner = inner
                .strip_suffix(q)
                .unwrap_or_else(|| panic!("line {no}: an unclosed quote"));
            assert!(
                !inner.contains(q) && !inner.contains('\\'),
                "line {no}: escapes are not read here"
            );
            return Yaml::Scalar(inner.to_owned(), true);
        }
    }
    assert!(
        !text.starts_with(['&', '*', '!', '{', '|', '>', '@', '`', '%']),
        "line {no}: `{text}` is not read here (anchor, tag, flow mapping or reserved)"
    );
    Yaml::Scalar(text.to_owned(), false)
}

/// The items of a flow sequence's inside, split at commas outside quotes.
fn split_flow(inner: &str, no: usize) -> Vec<String> {
    let mut items = Vec::new();
    let (mut cur, mut quote) = (String::new(), None);
    for c in inner.chars() {
        match (c, quote) {
            ('"' | '\'', None) => quote = Some(c),
            (c, Some(q)) if c == q => quote = None,
            (',', None) => {
                items.push(cur.trim().to_owned());
                cur.clear();
                continue;
            }
            ('[' | ']' | '{' | '}', None) => panic!("line {no}: nested flow collections"),
            _ => {}
        }
        cur.push(c);
    }
    assert!(quote.is_none(), "line {no}: an unclosed quote");
    if !cur.trim().is_empty() {
        items.push(cur.trim().to_owned());
    }
    items
}

impl Yaml {
    /// The node at a dotted path of keys; `None` if a key is missing.
    fn get(&self, path: &str) -> Option<&Yaml> {
        path.split('.').try_fold(self, |node, key| match node {
            Yaml::Map(entries) => entries.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        })
    }

    /// The node at `path`, which must be there.
    fn at(&self, path: &str) -> &Yaml {
        self.get(path)
            .unwrap_or_else(|| panic!("`{path}` missing in {self:?}"))
    }

    /// The string at `path` (a scalar, quoted or not).
    fn str(&self, path: &str) -> &str {
        match self.at(path) {
            Yaml::Scalar(s, _) => s,
            other => panic!("`{path}` is not a scalar: {other:?}"),
        }
    }

    /// The integer at `path`: a plain (unquoted) scalar, as Kubernetes' int32 fields need.
    fn int(&self, path: &str) -> i64 {
        match self.at(path) {
            Yaml::Scalar(s, false) => s
                .parse()
                .unwrap_or_else(|_| panic!("`{path}` = `{s}` is not an integer")),
            other => panic!("`{path}` is not a plain integer: {other:?}"),
        }
    }

    /// The items of the sequence at `path`.
    fn seq(&self, path: &str) -> &[Yaml] {
        match self.at(path) {
            Yaml::Seq(items) => items,
            other => panic!("`{path}` is not a sequence: {other:?}"),
        }
    }
}

#[test]
fn the_yaml_reader_reads_the_manifest_subset_and_nothing_else() {
    let docs = parse_yaml(
        "a: 1 # one\nb: \"2\"\nc:\n  - x: [\"p\", 'q # r']\n    y: >-\n      s\n      t\n  - z\n---\nd:\n- e\n",
    );
    assert_eq!(docs.len(), 2);
    assert_eq!(docs[0].int("a"), 1);
    assert_eq!(docs[0].at("b"), &Yaml::Scalar("2".into(), true));
    let c = docs[0].seq("c");
    assert_eq!(
        c[0].at("x"),
        &Yaml::Seq(vec![
            Yaml::Scalar("p".into(), true),
            Yaml::Scalar("q # r".into(), true)
        ])
    );
    assert_eq!(c[0].str("y"), "s t");
    assert_eq!(c[1], Yaml::Scalar("z".into(), false));
    assert_eq!(docs[1].seq("d"), [Yaml::Scalar("e".into(), false)]);
    for bad in ["a: &n 1\n", "a: {b: 1}\n", "a: 1\n  b: 2\n", "a: 1\na: 2\n"] {
        assert!(
            std::panic::catch_unwind(|| parse_yaml(bad)).is_err(),
            "accepted: {bad}"
        );
    }
}

/// The text the container runs: its command and args joined (`bash -c SCRIPT`).
fn container_script(container: &Yaml) -> String {
    let command: Vec<&str> = container
        .seq("command")
        .iter()
        .chain(
            container
                .get("args")
                .map_or(&[][..], |_| container.seq("args")),
        )
        .map(|y| match y {
            Yaml::Scalar(s, _) => s.as_str(),
            other => panic!("a command word that is not a string: {other:?}"),
        })
        .collect();
    assert!(
        matches!(command[..], ["bash" | "sh", "-c", _]),
        "the container must run its script in a shell (for ${{...}}): {command:?}"
    );
    command[2].to_owned()
}

/// The value of the container's environment variable `name`.
fn env_var<'a>(container: &'a Yaml, name: &str) -> &'a Yaml {
    container
        .seq("env")
        .iter()
        .find(|e| e.str("name") == name)
        .unwrap_or_else(|| panic!("no environment variable {name}"))
}

/// What every Job of the manifest needs, whatever its completion mode.
fn check_job(job: &Yaml, volumes_claimed: &[&str]) {
    assert_eq!(job.str("apiVersion"), "batch/v1");
    let pod = job.at("spec.template.spec");
    assert!(
        matches!(pod.str("restartPolicy"), "Never" | "OnFailure"),
        "a Job's pods restart Never or OnFailure"
    );
    let volumes: Vec<&str> = pod.seq("volumes").iter().map(|v| v.str("name")).collect();
    for v in pod.seq("volumes") {
        let claim = v.str("persistentVolumeClaim.claimName");
        assert!(
            volumes_claimed.contains(&claim),
            "volume claim {claim} is not in the manifest"
        );
    }
    let containers = pod.seq("containers");
    assert!(!containers.is_empty());
    for c in containers {
        assert!(!c.str("name").is_empty() && !c.str("image").is_empty());
        for m in c.seq("volumeMounts") {
            assert!(
                volumes.contains(&m.str("name")),
                "mount of an undeclared volume"
            );
        }
    }
}

#[test]
fn k8s_manifest_is_an_indexed_job_whose_shard_count_agrees() {
    let path = workspace().join("examples/cluster/k8s-table5-job.yaml");
    let docs = parse_yaml(&fs::read_to_string(&path).unwrap());
    let by_kind = |kind: &str| -> Vec<&Yaml> {
        docs.iter()
            .filter(|d| d.str("kind") == kind)
            .collect::<Vec<_>>()
    };
    let claims: Vec<&str> = by_kind("PersistentVolumeClaim")
        .iter()
        .map(|d| d.str("metadata.name"))
        .collect();
    for d in &docs {
        assert!(
            matches!(d.str("metadata.labels.step"), "shards" | "merge"),
            "every object is applied with one of the two steps (-l step=...)"
        );
    }
    let jobs = by_kind("Job");
    let step = |s: &str| -> &Yaml {
        let found: Vec<&&Yaml> = jobs
            .iter()
            .filter(|j| j.str("metadata.labels.step") == s)
            .collect();
        assert_eq!(found.len(), 1, "one Job of step {s}");
        found[0]
    };

    // The shards: an Indexed Job of N pods, pod K running shard K of N.
    let shards = step("shards");
    check_job(shards, &claims);
    assert_eq!(shards.str("spec.completionMode"), "Indexed");
    let n = shards.int("spec.completions");
    assert!(
        (1..=100_000).contains(&n),
        "an Indexed Job has 1 to 100000 completions"
    );
    let parallelism = shards.int("spec.parallelism");
    assert!(
        (1..=n).contains(&parallelism),
        "parallelism {parallelism} must be 1 to completions {n}"
    );
    let [container] = shards.seq("spec.template.spec.containers") else {
        panic!("one container per shard pod")
    };
    assert_eq!(
        env_var(container, "SHARDS").at("value"),
        &Yaml::Scalar(n.to_string(), true),
        "SHARDS (a quoted string) must be completions"
    );
    assert_eq!(
        env_var(container, "THREADS").str("valueFrom.resourceFieldRef.resource"),
        "requests.cpu"
    );
    container.str("resources.requests.cpu");
    let script = container_script(container);
    for needed in [
        "run table5",
        r#"--shard "${JOB_COMPLETION_INDEX}/${SHARDS}""#,
        r#"--threads "${THREADS}""#,
        r#"--out "/data/shards/${JOB_COMPLETION_INDEX}""#,
    ] {
        assert!(
            script.contains(needed),
            "the shard command lacks {needed}: {script}"
        );
    }

    // The merge: one pod, after every shard, reading every shard's directory.
    let merge = step("merge");
    check_job(merge, &claims);
    assert!(merge.get("spec.completionMode").is_none());
    assert_eq!(merge.int("spec.completions"), 1);
    let [container] = merge.seq("spec.template.spec.containers") else {
        panic!("one container in the merge pod")
    };
    let script = container_script(container);
    assert!(
        script.contains("merge /data/shards/*"),
        "the merge reads every shard: {script}"
    );
}

// ---------------------------------------------------------------------------------------------
// The SLURM script against a stand-in sbatch.

/// A stand-in for `sbatch` on one node of 2 CPUs: records each call in $SBATCH_LOG, refuses
/// `--test-only` of more than 2 CPUs per task as SLURM 22.05 does, and "submits" the rest.
const FAKE_SBATCH: &str = r#"#!/usr/bin/env bash
set -euo pipefail
printf '%s\n' "$*" >>"$SBATCH_LOG"
cpus=1 test_only=0
for a in "$@"; do
    case "$a" in
        --cpus-per-task=*) cpus="${a#*=}" ;;
        --test-only) test_only=1 ;;
    esac
done
if ((test_only)); then
    if ((cpus > 2)); then
        echo "allocation failure: Requested node configuration is not available" >&2
        exit 1
    fi
    echo "sbatch: Job 7 to start at 2030-01-01T00:00:00 using $cpus processors on nodes n1 in partition p" >&2
    exit 0
fi
echo "$(( $(wc -l <"$SBATCH_LOG") + 100 ))"
"#;

/// Runs the example with the stand-in sbatch first on PATH; returns (status, stdout, stderr,
/// the sbatch calls).
fn slurm_example(
    s: &Scratch,
    args: &[&str],
    env: &[(&str, &str)],
) -> (Option<i32>, String, String, Vec<String>) {
    let bin = s.0.join("bin");
    fs::create_dir_all(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    fs::write(&sbatch, FAKE_SBATCH).unwrap();
    Command::new("chmod")
        .arg("+x")
        .arg(&sbatch)
        .status()
        .unwrap();
    let log = s.0.join("sbatch.log");
    let _ = fs::remove_file(&log);
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut c = Command::new("bash");
    c.arg("examples/cluster/slurm-table5.sh")
        .args([
            "--dir",
            &s.path("run"),
            "--xtask",
            env!("CARGO_BIN_EXE_xtask"),
        ])
        .args(args)
        .current_dir(workspace())
        .env("PATH", path)
        .env("SBATCH_LOG", &log)
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("SHARDS")
        .env_remove("CPUS_PER_TASK");
    for (k, v) in env {
        c.env(k, v);
    }
    let o = c.output().unwrap();
    let calls = fs::read_to_string(&log)
        .unwrap_or_default()
        .lines()
        .map(str::to_owned)
        .collect();
    (
        o.status.code(),
        support::stdout(&o),
        support::stderr(&o),
        calls,
    )
}

#[test]
fn slurm_example_refuses_more_cpus_than_a_node_has_at_once_in_one_line() {
    let s = Scratch::new("slurm-refuse");
    let start = Instant::now();
    let (status, out, err, calls) =
        slurm_example(&s, &["--shards", "2", "--cpus-per-task", "3"], &[]);
    assert!(start.elapsed() < Duration::from_secs(10), "not at once");
    assert_eq!(status, Some(2), "{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(
        err.trim_end(),
        "slurm-table5: SLURM cannot run 2 shard tasks of 3 CPUs each (Requested node \
         configuration is not available): ask for fewer CPUs per task with --cpus-per-task or \
         CPUS_PER_TASK (`sinfo -o '%N %c'` lists the nodes' CPUs)"
    );
    assert_eq!(calls.len(), 1, "only the test: {calls:?}");
    assert!(calls[0].starts_with("--test-only --array=0-1 --cpus-per-task=3 "));
    assert!(
        !s.0.join("run/shards").exists(),
        "nothing prepared for a refused run"
    );
}

#[test]
fn slurm_example_derives_the_array_from_the_shard_count() {
    let s = Scratch::new("slurm-submit");
    let (status, out, err, calls) = slurm_example(
        &s,
        &["--", "--set", "trials=4"],
        &[("SHARDS", "5"), ("CPUS_PER_TASK", "2")],
    );
    assert_eq!(status, Some(0), "{err}");
    assert_eq!(calls.len(), 4, "two tests, two submissions: {calls:?}");
    let (tests, submissions) = calls.split_at(2);
    assert!(tests.iter().all(|c| c.starts_with("--test-only ")));
    let array = &submissions[0];
    assert!(
        array.starts_with("--parsable --array=0-4 --cpus-per-task=2 ")
            && array.contains(" --shards 5 --cpus-per-task 2 --seed 2025 ")
            && array.ends_with(" -- --set trials=4"),
        "{array}"
    );
    let merge = &submissions[1];
    assert!(
        merge.contains("--cpus-per-task=2 ")
            && merge.contains("--dependency=afterok:103 --kill-on-invalid-dep=yes")
            && merge.contains(" merge shards/* --out results --threads 2"),
        "{merge}"
    );
    assert!(
        out.starts_with("submitted job array 103 (5 shards of 2 CPUs) and merge job 104\n"),
        "{out}"
    );
}
