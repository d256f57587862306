# Bash completion for rtk (installed as share/bash-completion/completions/rtk).
# The subcommands come from `rtk --help` and each one's options from `rtk CMD --help`,
# so the completion always matches the rtk it completes.

_rtk_words() { # the words of `rtk ARGS --help` that look like options
    "${COMP_WORDS[0]}" "$@" --help 2>/dev/null | grep -oE '(^|[ ,])--?[a-z][a-z-]*' | tr -d ' ,' | sort -u
}

_rtk() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD - 1]} cmd=${COMP_WORDS[1]}
    if [ "$COMP_CWORD" -eq 1 ]; then
        local commands
        commands=$("${COMP_WORDS[0]}" --help 2>/dev/null | awk '/^commands:/ {on = 1; next} on && /^  [a-z-]/ {print $1}')
        mapfile -t COMPREPLY < <(compgen -W "$commands" -- "$cur")
        return
    fi
    case $prev in
    --assets | --missing)
        mapfile -t COMPREPLY < <(compgen -d -- "$cur")
        return ;;
    -o | --output | --diff | --svg | --junit | --write)
        mapfile -t COMPREPLY < <(compgen -f -- "$cur")
        return ;;
    --width | --height | --depth | --aa | --spp | --threads | --tile | --max-memory | --pixel | --sample | --min-psnr | --max-diff | --part | --region | --tiles | --parts)
        return ;;
    esac
    if [[ $cur == -* ]]; then
        mapfile -t COMPREPLY < <(compgen -W "$(_rtk_words "$cmd")" -- "$cur")
    else
        case $cmd in
        compare) mapfile -t COMPREPLY < <(compgen -f -X '!*.@(png|ppm)' -- "$cur") ;;
        stitch) mapfile -t COMPREPLY < <(compgen -f -X '!*.@(png|yaml|yml)' -- "$cur") ;;
        *) mapfile -t COMPREPLY < <(compgen -f -X '!*.@(yaml|yml|txt|sha256)' -- "$cur") ;;
        esac
        local d
        while IFS= read -r d; do COMPREPLY+=("$d/"); done < <(compgen -d -- "$cur")
        compopt -o nospace 2>/dev/null
    fi
}

complete -F _rtk rtk
