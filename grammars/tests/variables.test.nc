( SYNTAX TEST "source.fanuc-macro" "variables: null, local, common, system, indirect, named"
#0
(<- variable.language.null.fanuc-macro punctuation.definition.variable.fanuc-macro
(^ variable.language.null.fanuc-macro
#1=1.
(<-- variable.parameter.local.fanuc-macro
( ^ keyword.operator.assignment.fanuc-macro
(  ^^ constant.numeric.fanuc-macro
#33=#26
(<--- variable.parameter.local.fanuc-macro
(   ^^^ variable.parameter.local.fanuc-macro
#100=#101+#199
(<---- variable.other.common.fanuc-macro
(    ^^^^ variable.other.common.fanuc-macro
(         ^^^^ variable.other.common.fanuc-macro
#500=#999
(<---- variable.other.common.fanuc-macro
(    ^^^^ variable.other.common.fanuc-macro
#5221=#5041
(<- variable.language.system.fanuc-macro punctuation.definition.variable.fanuc-macro
(^^^^ variable.language.system.fanuc-macro
(     ^^^^^ variable.language.system.fanuc-macro
#3000=1
(<----- variable.language.system.fanuc-macro
#[#1+100]=0
(<- variable.other.indirect.fanuc-macro
(^ punctuation.section.brackets.begin.fanuc-macro
( ^^ variable.parameter.local.fanuc-macro
(   ^ keyword.operator.arithmetic.fanuc-macro
(    ^^^ constant.numeric.fanuc-macro
(       ^ punctuation.section.brackets.end.fanuc-macro
#[#[#1]]=#[#2+1]
(<- variable.other.indirect.fanuc-macro
( ^ variable.other.indirect.fanuc-macro
(        ^ variable.other.indirect.fanuc-macro
(          ^ variable.parameter.local.fanuc-macro
#1=#_ABSMT[1]
(  ^^^^^^^ variable.language.system.fanuc-macro
[#DEPTH]=0.5
(^^^^^^ variable.other.named.fanuc-macro
(        ^^^ constant.numeric.fanuc-macro
#1EQ#102
(<-- variable.parameter.local.fanuc-macro
( ^^ keyword.operator.comparison.fanuc-macro
(   ^^^^ variable.other.common.fanuc-macro
