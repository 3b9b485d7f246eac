//! The README's command examples, run as a user would run them, so that the
//! README cannot drift from what the program prints.
//!
//! Every ```` ```console ```` block of `README.md` is a session: lines
//! starting with `$ ` are commands, the lines after one are its expected
//! output (stdout, then stderr). The blocks run in order in one temporary
//! folder, so a later block can read what an earlier one wrote. `rocking`
//! is this crate's binary; any other command runs through `sh -c`.
//! Expected output is matched by snapbox: `[..]` stands for any text within
//! a line (the README writes timings so), `...` on a line of its own for any
//! number of lines.

use std::path::Path;
use std::process::Command;

/// One `$ command` of the README with the output it shows.
struct Example {
    /// The README line of the command (for messages).
    line: usize,
    /// The command line after `$ `.
    command: String,
    /// The output the README shows.
    expected: String,
}

/// The examples of every ```` ```console ```` block of `text`, in order.
fn examples(text: &str) -> Vec<Example> {
    let mut out: Vec<Example> = Vec::new();
    let mut in_console = false;
    for (i, line) in text.lines().enumerate() {
        let fence = line.trim_start();
        if fence.starts_with("```") {
            in_console = !in_console && fence.trim_start_matches('`').trim() == "console";
            continue;
        }
        if !in_console {
            continue;
        }
        if let Some(command) = line.strip_prefix("$ ") {
            out.push(Example {
                line: i + 1,
                command: command.to_string(),
                expected: String::new(),
            });
        } else if let Some(last) = out.last_mut() {
            last.expected.push_str(line);
            last.expected.push('\n');
        }
    }
    // A blank line separates one command's output from the next command.
    for e in &mut out {
        let trimmed = e.expected.trim_end().len();
        e.expected.truncate(trimmed);
        if !e.expected.is_empty() {
            e.expected.push('\n');
        }
    }
    out
}

/// Runs `command` in `dir`: `rocking …` is this crate's binary (its words
/// split on white space, a word in single quotes taken without them, as a
/// shell would: the README quotes `--set 'stack[0].static=0.2'`, whose
/// brackets some shells would glob), the rest goes to `sh -c`. Returns
/// stdout followed by stderr.
fn run(command: &str, dir: &Path) -> (bool, String) {
    let words: Vec<&str> = command
        .split_whitespace()
        .map(|w| w.strip_prefix('\'').and_then(|w| w.strip_suffix('\'')).unwrap_or(w))
        .collect();
    let output = if words.first() == Some(&"rocking") {
        Command::new(env!("CARGO_BIN_EXE_rocking"))
            .args(&words[1..])
            .current_dir(dir)
            .output()
    } else {
        Command::new("sh").arg("-c").arg(command).current_dir(dir).output()
    }
    .unwrap_or_else(|e| panic!("{command}: {e}"));
    let mut text = String::from_utf8_lossy(&output.stdout).into_owned();
    // A long command prints a progress line every 5 s when stderr is not a
    // terminal: how many depends on the machine's speed, so they are left
    // out, as timings are matched by `[..]`.
    for line in String::from_utf8_lossy(&output.stderr).lines() {
        if !line.starts_with("progress: ") {
            text.push_str(line);
            text.push('\n');
        }
    }
    (output.status.success(), text)
}

#[test]
fn the_readme_examples_print_what_the_readme_shows() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).expect("README.md");
    let examples = examples(&readme);
    assert!(
        examples.iter().filter(|e| e.command.starts_with("rocking")).count() >= 2,
        "the README shows at least a batch run and a sweep"
    );
    let dir = std::env::temp_dir().join(format!("rocking-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    // The README's commands run from the clone's root, where `assets/` is:
    // the scratch folder gets a link to it.
    std::os::unix::fs::symlink(concat!(env!("CARGO_MANIFEST_DIR"), "/assets"), dir.join("assets"))
        .expect("link assets");
    for e in &examples {
        let (ok, actual) = run(&e.command, &dir);
        assert!(ok, "README.md:{}: `{}` failed:\n{actual}", e.line, e.command);
        snapbox::assert_data_eq!(actual, e.expected.clone());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn examples_are_read_from_console_blocks_only() {
    let text = "```sh\n$ not this\n```\n\n```console\n$ rocking a\none\ntwo\n$ head b\n```\n";
    let ex = examples(text);
    assert_eq!(ex.len(), 2);
    assert_eq!((ex[0].line, ex[0].command.as_str()), (6, "rocking a"));
    assert_eq!(ex[0].expected, "one\ntwo\n");
    assert_eq!(ex[1].expected, "");
}

/// The README's table of configuration keys is the catalogue's, row for
/// row: a key added, renamed or re-documented in the catalogue fails here
/// until the README says the same.
#[test]
fn the_readme_key_table_is_the_catalogues() {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).expect("README.md");
    let (begin, end) = ("<!-- keys: made from the catalogue -->\n", "<!-- keys end -->");
    let start = readme.find(begin).expect("the README marks its key table") + begin.len();
    let stop = start + readme[start..].find(end).expect("the key table's end mark");
    let expected = rocking::sim::catalogue::markdown_table();
    assert!(
        readme[start..stop] == expected,
        "README.md's key table differs from the catalogue's; it should read:\n{expected}"
    );
}
