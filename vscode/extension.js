// Starts `lightrocks lsp` (or the configured command) for .lr and .lrd files.
const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const [command, ...args] = vscode.workspace
    .getConfiguration("lightrocks")
    .get("command", ["lightrocks", "lsp"]);
  client = new LanguageClient(
    "lightrocks",
    "LightRocks",
    { command, args },
    {
      documentSelector: [{ scheme: "file", language: "lightrocks" }],
    },
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
