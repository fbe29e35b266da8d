#!/usr/bin/env bash
# Installs the npm packages of web/ (three.js, glTF-Validator, fold) from
# web/package-lock.json, only when they are missing or out of date. Needs node
# and npm (scripts/setup.sh installs them from Debian when missing).
set -euo pipefail
cd "$(dirname "$0")/../web"
stamp=node_modules/.package-lock.json
if [ -f "$stamp" ] && [ "$stamp" -nt package-lock.json ] && [ "$stamp" -nt package.json ]; then
  echo "setup-web: npm packages present"
  exit 0
fi
echo "setup-web: installing npm packages"
npm ci --no-audit --no-fund --loglevel=error
