//! `docs/cli.md` is the CLI's own help, every command and subcommand, so it
//! cannot drift from the flags: this test makes it from `tetray --help`
//! and each `tetray <command> --help` and fails when the file differs.
//! `UPDATE_DOCS=1 cargo test --test cli_docs` writes it anew.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_tetray");

fn help(command: &[&str]) -> String {
    let out = Command::new(BIN)
        .args(command)
        .arg("--help")
        .env("COLUMNS", "100")
        .output()
        .expect("run tetray");
    assert!(out.status.success(), "tetray {command:?} --help failed");
    String::from_utf8(out.stdout).expect("UTF-8 help")
}

/// The subcommands a help text lists under "Commands:" (less `help`).
fn subcommands(help: &str) -> Vec<String> {
    let Some(start) = help.find("Commands:\n") else {
        return Vec::new();
    };
    help[start + "Commands:\n".len()..]
        .lines()
        .take_while(|line| !line.trim().is_empty())
        .filter(|line| line.starts_with("  ") && !line.starts_with("    "))
        .filter_map(|line| line.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_string)
        .collect()
}

/// The page: an introduction, then each command's help in a section.
fn page() -> String {
    let mut page = String::from(
        "# Command-line reference\n\n\
         Every command and flag of `tetray`, as `tetray <command> --help` prints\n\
         them (this page is made from the help itself; a test keeps it current).\n\
         What the options mean and when to choose them: [guide.md](guide.md).\n",
    );
    let mut queue: Vec<Vec<String>> = vec![Vec::new()];
    while let Some(command) = queue.first().cloned() {
        queue.remove(0);
        let args: Vec<&str> = command.iter().map(String::as_str).collect();
        let text = help(&args);
        let title = if command.is_empty() {
            "tetray".to_string()
        } else {
            format!("tetray {}", command.join(" "))
        };
        page.push_str(&format!("\n## `{title}`\n\n```text\n{}```\n", text));
        // Depth first: a command's subcommands come right after it.
        for (position, sub) in subcommands(&text).into_iter().enumerate() {
            let mut child = command.clone();
            child.push(sub);
            queue.insert(position, child);
        }
    }
    page
}

#[test]
fn the_cli_reference_is_the_help() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/cli.md");
    let page = page();
    if std::env::var("UPDATE_DOCS").as_deref() == Ok("1") {
        std::fs::write(&path, &page).expect("write docs/cli.md");
        return;
    }
    let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        on_disk == page,
        "docs/cli.md differs from the CLI's help: run `UPDATE_DOCS=1 cargo test --test \
         cli_docs` and commit it"
    );
    for command in [
        "render", "info", "bench", "view", "compare", "generate", "study",
    ] {
        assert!(
            page.contains(&format!("## `tetray {command}`")),
            "{command}"
        );
    }
}
