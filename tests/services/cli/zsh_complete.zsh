# Complete each line given as an argument in a real interactive zsh (in a pseudo-terminal,
# compinit loaded, `skydeck completion zsh` sourced): type it, press Tab, and print what the
# completion offered and the line after it, one result per line: OFFERED|...<TAB>BUFFER.
zmodload zsh/zpty
zpty shell zsh -f -i
zpty -w shell 'PS1=""; bindkey -e; autoload -Uz compinit && compinit -u -D'
zpty -w shell 'eval "$(skydeck completion zsh)"'
# Every candidate a completion function offers goes through compadd: note them, then add them.
zpty -w shell 'typeset -ga offered; compadd() { local -a options=("${@[1,(i)--]}") found; if (( ${options[(I)-[OAD]*]} )); then builtin compadd "$@"; return; fi; builtin compadd -O found "$@"; offered+=("${found[@]}"); builtin compadd "$@"; }'
zpty -w shell 'report() { print -r -- "<<${(j:|:)offered}>>[[$BUFFER]]"; offered=(); BUFFER=""; }; zle -N report; bindkey "^X" report'
zpty -w shell 'print READY''!'
zpty -r shell out '*READY!*'
for line in "$@"; do
    zpty -w -n shell "$line"$'\t\C-x'
    zpty -r shell out '*<<*>>\[\[*\]\]*'
    out=${out##*<<}
    print -r -- "${out%%>>*}"$'\t'"${${out#*\[\[}%%\]\]*}"
done
zpty -d shell
