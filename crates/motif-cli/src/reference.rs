//! `docs/cli.md`, the complete option reference, rendered from the command line's own clap
//! definitions (a test in `main` compares the committed file with it, so it cannot go stale).

use std::fmt::Write as _;

use clap::{Arg, Command};

/// Where the committed reference lives, relative to the workspace root.
pub(crate) const PATH: &str = "docs/cli.md";

/// The whole reference of `motif` (built: `command.build()` has run, so global options reach
/// every subcommand).
pub(crate) fn markdown(motif: &Command) -> String {
    let mut text = String::new();
    text.push_str(
        "# Command-line reference\n\n\
         Every option of every `motif` command, with its value, default and allowed range. This page is\n\
         generated from the command line's own definitions (the same text as `motif <command> --help`);\n\
         do not edit it by hand. A test fails when it is stale; regenerate it with\n\
         `MOTIF_BLESS=1 cargo test --release -p motif-cli cli_reference`.\n\n",
    );
    let commands: Vec<&Command> = motif.get_subcommands().filter(|command| !command.is_hide_set()).collect();
    text.push_str("| command | what it does |\n|---|---|\n");
    for command in &commands {
        let name = command.get_name();
        let _ = writeln!(text, "| [`motif {name}`](#motif-{name}) | {} |", cell(&about(command)));
    }
    text.push_str("\n## Global options\n\nEvery command accepts these, before or after its name.\n\n");
    options_table(&mut text, motif.get_arguments().filter(|arg| arg.is_global_set()));
    for command in commands {
        command_section(&mut text, command);
    }
    text
}

fn command_section(text: &mut String, command: &Command) {
    let _ = writeln!(text, "\n## motif {}\n", command.get_name());
    let long = command.get_long_about().or(command.get_about()).map(ToString::to_string).unwrap_or_default();
    let _ = writeln!(text, "{}\n", long.trim());
    let usage = command.clone().render_usage().to_string();
    let usage = usage.trim_start_matches("Usage:").trim();
    let _ = writeln!(text, "```text\n{usage}\n```\n");
    options_table(text, command.get_arguments().filter(|arg| !arg.is_global_set()));
}

fn options_table<'a>(text: &mut String, arguments: impl Iterator<Item = &'a Arg>) {
    text.push_str("| option | description | default |\n|---|---|---|\n");
    for arg in arguments.filter(|arg| !arg.is_hide_set() && !["help", "version"].contains(&arg.get_id().as_str())) {
        let _ = writeln!(text, "| {} | {} | {} |", cell(&spelling(arg)), cell(&description(arg)), cell(&default(arg)));
    }
}

/// `--flag <VALUE>` (with `-q, ` for a short form), or `<NAME>` for a positional argument.
fn spelling(arg: &Arg) -> String {
    let values = arg.get_value_names().map(|names| names.iter().map(|name| format!(" <{name}>")).collect::<String>());
    let takes_value = arg.get_action().takes_values();
    let value = if takes_value {
        values.unwrap_or_else(|| format!(" <{}>", arg.get_id().as_str().to_uppercase()))
    } else {
        String::new()
    };
    match (arg.get_short(), arg.get_long()) {
        (Some(short), Some(long)) => format!("`-{short}, --{long}{value}`"),
        (None, Some(long)) => format!("`--{long}{value}`"),
        _ => format!("`{}`", value.trim()),
    }
}

fn description(arg: &Arg) -> String {
    let help = arg.get_long_help().or(arg.get_help()).map(ToString::to_string).unwrap_or_default();
    let mut text = help.split_whitespace().collect::<Vec<_>>().join(" ");
    if !text.is_empty() && !text.ends_with(['.', ')', ']']) {
        text.push('.');
    }
    let choices: Vec<String> = arg
        .get_possible_values()
        .iter()
        .filter(|value| !value.is_hide_set())
        .map(|value| match value.get_help() {
            Some(help) => format!("`{}`: {help}", value.get_name()),
            None => format!("`{}`", value.get_name()),
        })
        .collect();
    if !choices.is_empty() && arg.get_action().takes_values() {
        let _ = write!(text, " One of: {}.", choices.join("; "));
    }
    if arg.is_required_set() {
        text.push_str(" Required.");
    }
    text
}

fn default(arg: &Arg) -> String {
    let values: Vec<String> =
        arg.get_default_values().iter().map(|value| value.to_string_lossy().into_owned()).collect();
    if values.is_empty() { "—".to_string() } else { format!("`{}`", values.join(",")) }
}

fn about(command: &Command) -> String {
    command.get_about().map(ToString::to_string).unwrap_or_default()
}

/// Text made safe for one Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}
